// The simulated Orion behind make_orion_sim(). Private to lib/sim: everyone else talks to it
// as a Device, in bytes. orion_sim.cpp runs time and the commands; orion_sim_output.cpp builds
// what the gimbal sends.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "geo/sampled_surface.hpp"
#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/orion/sim/laser.hpp"
#include "protocols/orion/sim/orion_sim.hpp"
#include "protocols/orion/sim/retract.hpp"
#include "sim/device.hpp"
#include "sim/path_follower.hpp"
#include "sim/platform.hpp"
#include "sim/pointing.hpp"

namespace gimbal::sim {

class OrionSim final : public Device {
  public:
    explicit OrionSim(const OrionSimOptions& options);

    void receive(std::span<const std::uint8_t> bytes, double now_s) override;
    void advance(double now_s, std::vector<std::uint8_t>& out) override;
    OrionCameraView camera_view() const;  // orion_sim_camera.cpp

  private:
    // What the axes are asked to do, from the latest command.
    enum class Demand {
        hold,             // motors off or calibrating: stay put
        mount_angles,     // slew to pan/tilt relative to the mount
        mount_rates,      // turn at pan/tilt rates relative to the mount
        inertial_angles,  // hold an azimuth/elevation in NED
        inertial_rates,   // turn the line of sight at azimuth/elevation rates
        look_at_point,    // geopoint
        look_down,        // path with pointDown and no points
        follow_path,      // path
    };

    struct Periodic {
        std::uint8_t id;
        double period_s;
        std::uint64_t next = 0;  // index of the next tick; tick k is due at k * period_s
        double due() const { return static_cast<double>(next) * period_s; }
    };

    // --- time (orion_sim.cpp) ---
    void run_until(double now_s);
    void step_to(double t);
    void step(double dt);
    void update_platform(double t);
    std::uint32_t system_time_ms() const;
    double gps_seconds() const;

    // --- input (orion_sim.cpp) ---
    void handle(const orion::Frame& frame);
    void answer_request(std::uint8_t id);
    void answer_uart_config(std::uint8_t port);
    void store_setting(std::uint8_t id, std::span<const std::uint8_t> data);
    void on_cmd(const orion::PanTiltCmd& cmd);
    void on_geopoint(const orion::GeopointCmd& cmd);
    void on_path(const orion::Path& path);
    void on_laser(const orion::LaserCmd& cmd);
    void on_autopilot(const orion::AutopilotData& ap);
    void on_stare_ack(const orion::StareAck& ack);
    void on_gps(const orion::GpsData& gps);

    // --- output (orion_sim_output.cpp) ---
    template <class P>
    void send(const P& packet);
    void send_frame(std::uint8_t id, std::span<const std::uint8_t> data);
    void emit_periodic(std::uint8_t id);
    void send_stare_start(const StareBegin& begin);
    orion::GeolocateTelemetry telemetry() const;
    orion::Performance performance();
    orion::Diagnostics diagnostics();
    orion::InsQuality ins_quality();
    orion::GpsData gps_data() const;
    orion::LaserStates laser_states() const;
    orion::RetractStatus retract_status() const;
    orion::SoftwareDiagnostics software_diagnostics();
    orion::Vibration vibration();
    orion::NetworkDiagnostics network_diagnostics() const;
    // Where the line of sight meets the terrain (or the commanded range), relative to the
    // gimbal; zero when it meets nothing within reach of the I16 field.
    Vec3 line_of_sight_vector(orion::RangeSource& source) const;
    Vec3 line_of_sight_dir() const;
    // Where a ray from the gimbal first meets the ground (flat or the analytic terrain).
    std::optional<Vec3> ground_hit(Vec3 dir_ecef) const;
    double noise(double sigma);

    OrionSimOptions options_;
    // The analytic terrain (sim/terrain.hpp) unless options_.terrain_alt_m sets flat ground.
    std::unique_ptr<geo::SampledSurface> terrain_;
    CirclePlatform circle_;
    PathOptions path_options_;
    double on_target_rad_;

    // time
    bool started_ = false;
    double t0_ = 0;  // caller's clock at the model's start
    double t_ = 0;   // model time, seconds since the start
    std::vector<Periodic> schedule_;

    // wire
    orion::Framer framer_;
    std::vector<std::uint8_t> pending_;  // bytes to hand out on the next advance()
    std::uint64_t tx_bytes_ = 0;
    std::uint64_t tx_packets_ = 0;

    // platform and pointing
    PlatformState platform_;
    Mat3 mount_to_ecef_;
    GimbalAxes axes_;
    orion::Mode mode_ = orion::Mode::position;
    orion::PanTiltCmd last_cmd_;
    Demand demand_ = Demand::mount_angles;
    PanTilt target_angles_;  // mount_angles
    bool within_limits_ = true;
    PanTilt rates_;               // mount_rates / inertial_rates, rad/s
    double impulse_left_s_ = -1;  // < 0: no impulse time, rates run until the next command
    PanTilt inertial_;            // azimuth / elevation, rad
    Vec3 geo_point_;              // ECEF
    Vec3 geo_vel_ned_;
    bool geo_stare_pending_ = false;
    std::optional<PathFollower> path_;
    std::uint32_t stare_system_time_ms_ = 0;
    double pointing_error_ = 0;  // rad, line of sight vs where the demand wants it

    // external inputs
    std::optional<orion::GpsData> gps_fix_;
    double gps_fix_t_ = 0;
    double range_m_ = 0;
    double range_until_t_ = -1;
    orion::RangeSource range_source_ = orion::RangeSource::none;

    // payload and the rest
    orion::Cameras cameras_;
    std::vector<double> zoom_;
    std::uint8_t active_camera_ = 0;
    LaserBank lasers_;
    Retract retract_;
    std::map<std::uint8_t, orion::Payload> settings_;      // config packets by id
    std::map<std::uint8_t, orion::Payload> uart_configs_;  // UartConfig by port
    std::mt19937 rng_;
};

template <class P>
void OrionSim::send(const P& packet) {
    orion::Payload payload;
    if (!orion::encode(packet, payload)) return;  // cannot happen for packets built here
    send_frame(P::id, payload.view());
}

}  // namespace gimbal::sim
