// A simulated SIYI gimbal camera (the later gimbal-sim --protocol siyi / gimbald --sim siyi):
// speaks SIYI's SDK protocol as the camera does - replies with CTRL ack_pack and its own
// sequence, pushes the attitude stream at the rate 0x25 asks for (and the ZT30's laser range
// at the rangefinder's own rate), the 0x0B feedback after a photo or a recording toggle - and
// moves like one: the model's slew rate and angle limits, absolute angles (0x0E), speeds
// (0x07), centering (0x08), zoom within the model's range (0x0F, 0x05), recording (0x0C).
// Unknown commands and frames too short for their message get no reply, like a camera that
// does not support them; garbage between frames is skipped by the framer. Pure: time is
// passed in. Behaviour the SDK leaves open is listed in docs/siyi.md "The simulated gimbal".
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "protocols/siyi/codec/models.hpp"
#include "protocols/siyi/sim/siyi_sim_motion.hpp"
#include "sim/device.hpp"

namespace gimbal::protocols {

struct SiyiSimOptions {
    siyi::Model model = siyi::Model::zt30;
    std::uint32_t seed = 1;             // the hardware id's serial digits, the angle noise
    double yaw_deg = 0, pitch_deg = 0;  // where the axes start (SIYI frame)
    double zoom = 1;
    double angle_noise_deg = 0;  // 1 sigma on the reported angles
    // Until this long after the first advance() the firmware versions read 0.0.0, as a real
    // camera's do while it starts (up to 30 s).
    double boot_time_s = 0;
    bool sd_card = true;  // without one a recording fails (0x0B record_failed, 0x0A no_card)
    // The laser (ZT30) measures to flat ground this far below the camera.
    double height_above_ground_m = 100;
    double laser_rate_hz = 10;  // the rangefinder's own output rate (0x25 laser stream)
    // Where the aircraft is until it says (0x3E): only the rendered video uses it (the laser's
    // target needs the aircraft's own position). The simulated Orion's circle centre, above
    // the simulator's terrain (sim/terrain.hpp), whose geoid lies 21 m below the ellipsoid.
    double lat_deg = 45.7, lon_deg = -121.5;
    double alt_msl_m = 1500;
    double geoid_undulation_m = -21;
};

// The aircraft as the camera last heard of it (0x3E position, 0x22 attitude).
struct SiyiSimAircraft {
    double lat_deg = 0, lon_deg = 0;
    double alt_msl_m = 0, alt_ellipsoid_m = 0;
    double roll_deg = 0, pitch_deg = 0, yaw_deg = 0;  // yaw: heading from north
};

struct SiyiSimStats {
    std::uint64_t handled = 0;      // frames acted on
    std::uint64_t unknown = 0;      // frames of a CMD_ID the camera does not know
    std::uint64_t too_short = 0;    // frames too short for their message
    std::uint64_t unsupported = 0;  // known commands this model does not answer
};

class SiyiSim final : public sim::Device {
  public:
    explicit SiyiSim(const SiyiSimOptions& options);

    void receive(std::span<const std::uint8_t> bytes, double now_s) override;
    void advance(double now_s, std::vector<std::uint8_t>& out) override;

    const siyi::ModelInfo& model() const { return model_; }
    const std::string& hardware_id() const { return hardware_id_; }
    double yaw_deg() const { return motion_.yaw(); }
    double pitch_deg() const { return motion_.pitch(); }
    double zoom() const { return motion_.zoom(); }
    double time_s() const { return time_; }  // the model's time (the last advance)
    // The aircraft's position and attitude: 0x3E and 0x22 as last received, else the options'
    // position, level and heading north.
    SiyiSimAircraft aircraft() const;
    const SiyiSimOptions& options() const { return options_; }
    bool recording() const { return recording_; }
    siyi::MotionMode motion_mode() const { return motion_mode_; }
    // What the rangefinder reads now (nullopt: no laser, or nothing within 5-1200 m).
    std::optional<double> laser_range_m() const;
    const SiyiSimStats& stats() const { return stats_; }
    const siyi::FramerStats& framer_stats() const { return framer_.stats(); }

  private:
    struct Stream {
        double period_s = 0;  // 0: off
        double next_s = 0;
    };

    void run_until(double now_s);
    void emit_streams();
    void on_frame(const siyi::Frame& frame);
    bool handle(const siyi::ToGimbal& message);
    template <class M>
    void send(const M& message);
    void send_firmware_version();
    siyi::GimbalAttitude attitude();
    siyi::CameraSystemInfo system_info() const;
    siyi::LaserTarget laser_target() const;
    void capture(siyi::CaptureFunction f);
    void set_stream(siyi::StreamType type, siyi::StreamRate rate);
    double noise();

    SiyiSimOptions options_;
    const siyi::ModelInfo& model_;
    siyi::SimMotion motion_;
    siyi::Framer framer_;
    std::mt19937 rng_;
    std::string hardware_id_;
    bool started_ = false;
    double start_s_ = 0, time_ = 0;
    std::uint16_t seq_ = 0;
    bool recording_ = false;
    siyi::MotionMode motion_mode_ = siyi::MotionMode::follow;
    Stream attitude_stream_, laser_stream_, encoder_stream_;
    // What the aircraft last told the camera (0x22, 0x3E).
    std::optional<siyi::AircraftAttitude> aircraft_attitude_;
    std::optional<siyi::RawGps> aircraft_position_;
    std::vector<std::uint8_t> outbox_;
    SiyiSimStats stats_;
};

std::unique_ptr<sim::Device> make_siyi_sim(const SiyiSimOptions& options);

}  // namespace gimbal::protocols
