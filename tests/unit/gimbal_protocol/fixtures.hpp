// Shared by the gimbal-protocol tests: two gimbals (an Orion and a Viewpro), their typed state
// as gimbald's sessions hold it (and a MAVLink gimbal device's), and command builders.
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "gimbal_protocol/commands.hpp"
#include "gimbal_protocol/status.hpp"
#include "protocols/mavlink_device/mavlink_device_capabilities.hpp"
#include "protocols/orion/orion_capabilities.hpp"
#include "protocols/viewpro/viewpro_capabilities.hpp"

namespace gptest {

using namespace gimbal::gimbal_protocol;
namespace mav = gimbal::mavlink;
using mav::MavResult;

inline const float NaN = std::numeric_limits<float>::quiet_NaN();
inline const float Inf = std::numeric_limits<float>::infinity();
inline const MavId gcs{255, 190};
inline const MavId other_gcs{254, 190};

inline std::vector<ExposedGimbal> two_gimbals() {
    return expose({{"main", "orion"}, {"nose", "viewpro"}});
}

// A gimbal's typed state as its session would hold it - what it reported, and its
// capabilities bound to that - and the view the mapping reads of it. Held by a shared pointer:
// the capabilities point into it.
struct TestGimbal {
    virtual ~TestGimbal() = default;
    virtual const gimbal::session::Capabilities& capabilities() const = 0;
    virtual const gimbal::state::Telemetry* telemetry() const { return nullptr; }
    bool connected = true;
    bool stale = false;
    std::optional<gimbal::state::VideoState> video;
    bool visual_tracking = false;  // video.tracking: STATE `track` is `track`
    std::optional<gimbal::state::TrackState> track;

    gimbal::session::GimbalView view() const {
        gimbal::session::GimbalView v{&capabilities(), telemetry(), connected, stale, {}, {}};
        if (video) v.video = [video = video] { return video; };
        if (visual_tracking) v.track = [track = track] { return track; };
        return v;
    }
};

struct OrionGimbal final : TestGimbal {
    gimbal::state::OrionData data;
    gimbal::protocols::OrionCapabilities caps{data};
    const gimbal::session::Capabilities& capabilities() const override { return caps; }
    const gimbal::state::Telemetry* telemetry() const override {
        return data.telemetry ? &data.telemetry->shared : nullptr;
    }
    gimbal::state::Telemetry& shared() { return data.telemetry->shared; }
    void set_quat(const gimbal::geo::Quat& q) {
        data.telemetry->packet.quat = {q.w, q.x, q.y, q.z};
    }
};

struct ViewproGimbal final : TestGimbal {
    std::optional<gimbal::viewpro::Output> output;
    gimbal::protocols::ViewproCapabilities caps{output};
    const gimbal::session::Capabilities& capabilities() const override { return caps; }
};

struct DeviceGimbal final : TestGimbal {
    gimbal::protocols::MavlinkDeviceData data;
    gimbal::protocols::MavlinkDeviceCapabilities caps{data};
    const gimbal::session::Capabilities& capabilities() const override { return caps; }
    const gimbal::state::Telemetry* telemetry() const override {
        return data.telemetry ? &*data.telemetry : nullptr;
    }
};

using AnyGimbal = std::shared_ptr<const TestGimbal>;

// A fixture: changed through ->, passed where a view (or a gimbal for states()) is wanted.
template <class G>
class Fixture {
  public:
    Fixture() : g_(std::make_shared<G>()) {}
    G* operator->() const { return g_.get(); }
    operator gimbal::session::GimbalView() const { return g_->view(); }
    operator AnyGimbal() const { return g_; }

  private:
    std::shared_ptr<G> g_;
};

inline constexpr double deg = 3.14159265358979323846 / 180.0;

// An Orion that has reported nothing yet.
inline Fixture<OrionGimbal> empty_orion() {
    return {};
}

// An Orion over the Columbia river gorge: telemetry, LIMITS and CAMERAS.
inline Fixture<OrionGimbal> orion_state() {
    Fixture<OrionGimbal> g;
    gimbal::state::OrionTelemetry t;
    t.packet.quat = {1.0, 0.0, 0.0, 0.0};
    auto& s = t.shared;
    s.lat = 45.0;
    s.lon = -121.0;
    s.alt = 1500.0;
    s.alt_msl = 1521.0;
    s.geoid_undulation = -21.0;
    s.pan = 30.0;
    s.tilt = -20.0;
    s.hfov = 40.0;
    s.vfov = 30.0;
    s.target = gimbal::state::GeoPoint{45.01, -121.0, 79.0};
    g->data.telemetry = t;
    gimbal::orion::Limits limits;
    limits.min_pos = {-180.0 * deg, -120.0 * deg};
    limits.max_pos = {180.0 * deg, 30.0 * deg};
    g->data.packets.limits = gimbal::state::Received<gimbal::orion::Limits>{limits, {}, 0};
    gimbal::orion::CameraSettings cam;
    cam.min_focal_length_mm = 4.3;
    cam.max_focal_length_mm = 129.0;
    cam.array_width = 1920;
    cam.array_height = 1080;
    cam.pixel_pitch_mm = 0.0029;
    gimbal::orion::Cameras cameras;
    cameras.cameras = {cam};
    g->data.packets.cameras = gimbal::state::Received<gimbal::orion::Cameras>{cameras, {}, 0};
    return g;
}

// A Viewpro that has sent no output frame yet.
inline Fixture<ViewproGimbal> empty_viewpro() {
    return {};
}

inline Fixture<ViewproGimbal> viewpro_state() {
    Fixture<ViewproGimbal> g;
    gimbal::viewpro::Output o;
    o.format = gimbal::viewpro::OutFormat::out3;
    o.gimbal_roll_deg = 0.0;
    o.gimbal_pitch_deg = -45.0;
    o.gimbal_yaw_deg = 10.0;
    o.uav_roll_deg = 0.0;
    o.uav_pitch_deg = 0.0;
    o.uav_yaw_deg = 90.0;
    o.uav_lat_deg = 6.94;
    o.uav_lon_deg = 79.88;
    o.uav_alt_msl_m = 300.0;
    o.target_lat_deg = 6.945;
    o.target_lon_deg = 79.88;
    g->output = o;
    return g;
}

// A MAVLink gimbal device that has reported nothing yet.
inline Fixture<DeviceGimbal> empty_device() {
    return {};
}

// A MAVLink gimbal device as its session reports it: attitude from
// GIMBAL_DEVICE_ATTITUDE_STATUS (yaw in the vehicle frame), the vehicle's fix, its name and
// limits from GIMBAL_DEVICE_INFORMATION.
inline Fixture<DeviceGimbal> device_state() {
    Fixture<DeviceGimbal> g;
    gimbal::state::Telemetry t;
    t.pan = 15.0;
    t.tilt = -30.0;
    t.hfov = 60.0;
    t.vfov = 34.0;
    t.lat = 45.7;
    t.lon = -121.5;
    t.alt = 1079.0;
    t.alt_msl = 1100.0;
    t.geoid_undulation = -21.0;
    t.roll = 0.0;
    t.pitch = 0.0;
    t.yaw = 90.0;
    t.target = gimbal::state::GeoPoint{45.69, -121.49, 79.0};
    g->data.telemetry = t;
    gimbal::mavlink::GimbalDeviceInformation info;
    gimbal::mavlink::set_text(info.vendor_name, "Gremsy");
    gimbal::mavlink::set_text(info.model_name, "T3V3");
    info.firmware_version = 7 | (4 << 8) | (2 << 16);
    info.pitch_min = static_cast<float>(-120.0 * deg);
    info.pitch_max = static_cast<float>(45.0 * deg);
    info.yaw_min = static_cast<float>(-170.0 * deg);
    info.yaw_max = static_cast<float>(170.0 * deg);
    g->data.information = info;
    gimbal::protocols::DeviceAttitude a;
    a.roll_deg = 0.0;
    a.pitch_deg = -30.0;
    a.yaw_deg = 15.0;
    a.earth_frame = false;
    g->data.attitude = a;
    return g;
}

// The gimbals "main" and "nose" (two_gimbals()).
inline StateLookup states(AnyGimbal main = orion_state(), AnyGimbal nose = viewpro_state()) {
    return [main, nose](const std::string& name) {
        return name == "main" ? main->view() : nose->view();
    };
}

inline VehicleView vehicle(std::optional<double> heading = 90.0,
                           std::optional<double> home = 100.0) {
    return {heading, home};
}

// Commands go to component 0 (every gimbal manager) unless the test names one.
inline CommandView long_cmd(std::uint16_t command, std::array<float, 7> p,
                            std::uint8_t component = 0) {
    mav::CommandLong c;
    c.command = command;
    c.param = p;
    c.target_system = 1;
    c.target_component = component;
    return view(c);
}

inline CommandView int_cmd(std::uint16_t command, std::array<float, 4> p, std::int32_t x,
                           std::int32_t y, float z, std::uint8_t frame,
                           std::uint8_t component = 0) {
    mav::CommandInt c;
    c.command = command;
    c.param1 = p[0];
    c.param2 = p[1];
    c.param3 = p[2];
    c.param4 = p[3];
    c.x = x;
    c.y = y;
    c.z = z;
    c.frame = frame;
    c.target_system = 1;
    c.target_component = component;
    return view(c);
}

// No request ever asks for the laser.
inline bool no_laser(const Mapped& m) {
    for (const auto& r : m.requests)
        if (r.request.value("cmd", "") == "laser") return false;
    return true;
}

}  // namespace gptest
