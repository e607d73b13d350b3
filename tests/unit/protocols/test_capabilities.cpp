// Typed capabilities (session/capabilities.hpp) of every protocol, checked against what the
// MAVLink gimbal manager (lib/gimbal_protocol) does per protocol today, over a grid of
// commands and STATEs: the same requests, the same refusals (unsupported / not yet), the same
// line of sight, view, limits, identity and camera. When the mapping moves onto the
// capabilities it cannot change behaviour.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "../gimbal_protocol/fixtures.hpp"
#include "protocols/registry.hpp"

using namespace gptest;
using nlohmann::json;
namespace caps = gimbal::session;
namespace protocols = gimbal::protocols;

namespace {

constexpr double rad_to_deg = 180.0 / std::numbers::pi;
constexpr double deg_to_rad = std::numbers::pi / 180.0;

const caps::Capabilities& capabilities_of(const std::string& protocol) {
    return *protocols::find(protocol)->capabilities;
}

// The single-gimbal manager the old mapping runs, and its state.
struct One {
    std::string name, protocol;
    json state;
};

std::vector<One> gimbals(bool with_data) {
    json orion = orion_state();
    json viewpro = viewpro_state();
    if (!with_data) {
        orion.erase("telemetry");
        orion.erase("cameras");
        orion.erase("limits");
        viewpro.erase("output");
    }
    return {{"main", "orion", orion}, {"nose", "viewpro", viewpro}};
}

Mapped old_mapping(const One& g, const gimbal::mavlink::Payload& payload, const VehicleView& v) {
    GimbalManager m(expose({{g.name, g.protocol}}));
    return m.message(payload, gcs, v, [&](const std::string&) { return g.state; });
}

Mapped old_command(const One& g, const CommandView& c, const VehicleView& v) {
    GimbalManager m(expose({{g.name, g.protocol}}));
    return m.command(
        c, gcs, v, [&](const std::string&) { return g.state; }, 0);
}

// The old mapping's one request without "gimbal", or its refusal as a capability would say.
void same(const Mapped& old, const caps::Request& now) {
    if (old.requests.empty()) {
        INFO("old: " << static_cast<int>(old.result) << " " << old.reason);
        REQUIRE_FALSE(now.ok());
        CHECK(now.error().message == old.reason);
        if (old.result == MavResult::temporarily_rejected)
            CHECK(now.error().code == gimbal::command::ErrorCode::unavailable);
        else
            CHECK(now.error().code == gimbal::command::ErrorCode::unsupported);
        return;
    }
    REQUIRE(old.requests.size() == 1);
    json want = old.requests[0].request;
    want.erase("gimbal");
    REQUIRE(now.ok());
    CHECK(now.value() == want);
}

}  // namespace

TEST_CASE("point_angles and rate: the gimbal manager's pitch/yaw mapping, per protocol") {
    const float values[] = {NaN, -30.5f, 12.25f, 170.0f};
    const float rates[] = {NaN, 5.0f};
    for (const bool with_data : {true, false})
        for (const auto& g : gimbals(with_data))
            for (const float pitch : values)
                for (const float yaw : values)
                    for (const float rate : rates)
                        for (const std::uint32_t flags : {0u, 16u})  // YAW_IN_EARTH_FRAME
                            for (const auto heading :
                                 {std::optional<double>(), std::optional(100.0)}) {
                                INFO(g.protocol << " data " << with_data << " pitch " << pitch
                                                << " yaw " << yaw << " rate " << rate << " flags "
                                                << flags);
                                mav::GimbalManagerSetPitchyaw py;
                                py.gimbal_device_id = 1;
                                py.flags = flags;
                                py.pitch = static_cast<float>(pitch * deg_to_rad);
                                py.yaw = static_cast<float>(yaw * deg_to_rad);
                                py.pitch_rate = static_cast<float>(rate * deg_to_rad);
                                py.yaw_rate = static_cast<float>(-rate * deg_to_rad);
                                const Mapped old = old_mapping(g, py, {heading, 100.0});
                                const auto deg = [](float r) -> std::optional<double> {
                                    if (std::isnan(r)) return std::nullopt;
                                    return r * rad_to_deg;
                                };
                                const auto& c = capabilities_of(g.protocol);
                                if (!std::isnan(pitch) || !std::isnan(yaw)) {
                                    caps::AnglesTarget t;
                                    t.pitch_deg = deg(py.pitch);
                                    t.yaw_deg = deg(py.yaw);
                                    t.yaw_frame =
                                        flags ? caps::YawFrame::earth : caps::YawFrame::vehicle;
                                    t.vehicle_heading_deg = heading;
                                    same(old, c.point_angles(g.state, t));
                                } else if (!std::isnan(rate)) {
                                    same(old, c.rate(g.state, {py.pitch_rate * rad_to_deg,
                                                               py.yaw_rate * rad_to_deg}));
                                }
                            }
}

TEST_CASE("absolute_angles: complete angles and rates read nothing from STATE") {
    // The MAVLink mapping passes an empty STATE when a gimbal claims this: the answer must be
    // the one the real STATE gives.
    const std::vector<std::pair<std::string, json>> states = {
        {"orion", orion_state()}, {"viewpro", viewpro_state()}, {"mavlink", device_state()}};
    int claimed = 0;
    for (const auto& [protocol, state] : states) {
        const auto& c = capabilities_of(protocol);
        INFO(protocol);
        if (!c.features().absolute_angles) {
            // A gimbal stepped from where it looks now cannot do without its STATE.
            CHECK_FALSE(
                c.point_angles(json::object(), {-10.0, 20.0, caps::YawFrame::vehicle, 100.0}).ok());
            continue;
        }
        ++claimed;
        for (const auto frame : {caps::YawFrame::vehicle, caps::YawFrame::earth})
            for (const double pitch : {-90.0, -10.5, 30.0})
                for (const double yaw : {-170.0, 0.0, 95.25}) {
                    const caps::AnglesTarget t{pitch, yaw, frame, 100.0};
                    const auto with = c.point_angles(state, t);
                    const auto without = c.point_angles(json::object(), t);
                    REQUIRE(with.ok() == without.ok());
                    if (with.ok()) CHECK(with.value() == without.value());
                }
        const caps::RateTarget r{5.0, -3.0};
        CHECK(c.rate(state, r).ok() == c.rate(json::object(), r).ok());
        if (c.rate(state, r).ok())
            CHECK(c.rate(state, r).value() == c.rate(json::object(), r).value());
    }
    CHECK(claimed == 2);  // the Orion and the MAVLink device take absolute angles
}

TEST_CASE("geopoint and stop: DO_SET_ROI_LOCATION and DO_SET_ROI_NONE, per protocol") {
    for (const auto& g : gimbals(true)) {
        INFO(g.protocol);
        const auto& c = capabilities_of(g.protocol);
        const Mapped roi =
            old_command(g,
                        int_cmd(mav::mav_cmd::do_set_roi_location, {1, 0, 0, 0}, 473977420,
                                85455940, 488.5f, mav::mav_frame::global_int),
                        vehicle());
        same(roi, c.geopoint(g.state, {47.397742, 8.545594, 488.5}));
        const Mapped none = old_command(
            g, long_cmd(mav::mav_cmd::do_set_roi_none, {1, 0, 0, 0, 0, 0, 0}), vehicle());
        same(none, c.stop(g.state));
        CHECK(c.features().geopoint == !roi.requests.empty());
    }
}

TEST_CASE("zoom: SET_CAMERA_ZOOM range and continuous, per protocol") {
    for (const bool with_data : {true, false})
        for (const auto& g : gimbals(with_data))
            for (const auto& [type, value] :
                 std::vector<std::pair<float, float>>{{mav::zoom_type::range, 0},
                                                      {mav::zoom_type::range, 37.5f},
                                                      {mav::zoom_type::range, 100},
                                                      {mav::zoom_type::continuous, 1},
                                                      {mav::zoom_type::continuous, -1}}) {
                INFO(g.protocol << " data " << with_data << " type " << type << " value " << value);
                const Mapped old = old_command(
                    g, long_cmd(mav::mav_cmd::set_camera_zoom, {type, value, 1, 0, 0, 0, 0}),
                    vehicle());
                const caps::ZoomTarget t{type == mav::zoom_type::range
                                             ? caps::ZoomKind::range_percent
                                             : caps::ZoomKind::continuous,
                                         value};
                same(old, capabilities_of(g.protocol).zoom(g.state, t));
            }
}

TEST_CASE("line of sight, view, identity, limits and camera: the manager's status messages") {
    for (const bool with_data : {true, false})
        for (const auto& g : gimbals(with_data)) {
            INFO(g.protocol << " data " << with_data);
            const auto& c = capabilities_of(g.protocol);
            const ExposedGimbal exposed{g.name, g.protocol, 1};

            const auto old_los = line_of_sight(g.state, g.protocol);
            const auto los = c.line_of_sight(g.state);
            REQUIRE(old_los.has_value() == los.has_value());
            if (los) {
                CHECK(los->w == Approx(old_los->w));
                CHECK(los->x == Approx(old_los->x));
                CHECK(los->y == Approx(old_los->y));
                CHECK(los->z == Approx(old_los->z));
            }

            const auto fov = fov_status(exposed, g.state, 0);
            const auto v = c.view(g.state);
            const auto e7 = [](std::optional<double> d) {
                return d ? static_cast<std::int32_t>(std::lround(*d * 1e7))
                         : mav::CameraFovStatus::unknown;
            };
            const auto mm = [](std::optional<double> m) {
                return m ? static_cast<std::int32_t>(std::lround(*m * 1000))
                         : mav::CameraFovStatus::unknown;
            };
            CHECK(fov.lat_camera == e7(v.lat_deg));
            CHECK(fov.lon_camera == e7(v.lon_deg));
            CHECK(fov.alt_camera == mm(v.alt_msl_m));
            CHECK(fov.lat_image == e7(v.target_lat_deg));
            CHECK(fov.lon_image == e7(v.target_lon_deg));
            CHECK(fov.alt_image == mm(v.target_alt_msl_m));
            CHECK(std::isnan(fov.hfov) == !v.hfov_deg.has_value());
            if (v.hfov_deg) CHECK(fov.hfov == Approx(*v.hfov_deg));
            if (v.vfov_deg) CHECK(fov.vfov == Approx(*v.vfov_deg));

            const auto info = device_information(exposed, g.state, 0);
            const auto id = c.identity(g.state);
            const auto text = [](const auto& bytes) {
                return std::string(reinterpret_cast<const char*>(bytes.data()));
            };
            CHECK(text(info.vendor_name) == id.vendor);
            CHECK(text(info.model_name) == id.model);
            const auto l = c.limits(g.state);
            const auto rad = [](std::optional<double> d) {
                return d ? static_cast<float>(*d * deg_to_rad) : mav::nan_f;
            };
            for (const auto& [old, now] : {std::pair{info.yaw_min, rad(l.pan_min_deg)},
                                           {info.yaw_max, rad(l.pan_max_deg)},
                                           {info.pitch_min, rad(l.tilt_min_deg)},
                                           {info.pitch_max, rad(l.tilt_max_deg)}}) {
                CHECK(std::isnan(old) == std::isnan(now));
                if (!std::isnan(old)) CHECK(old == Approx(now));
            }
            namespace cap = mav::gimbal_cap;
            const auto f = c.features();
            std::uint32_t flags = cap::has_pitch_axis | cap::has_yaw_axis | cap::has_yaw_follow;
            if (f.pitch_lock) flags |= cap::has_pitch_lock;
            if (f.yaw_lock) flags |= cap::has_yaw_lock;
            if (f.yaw_in_earth_frame) flags |= cap::supports_yaw_in_earth_frame;
            if (f.infinite_yaw) flags |= cap::supports_infinite_yaw;
            if (f.geopoint) flags |= cap::can_point_location_global;
            CHECK(info.cap_flags2 == flags);

            const auto cam = camera_information(exposed, g.state, 0);
            const auto camera = c.camera(g.state);
            CHECK((cam.flags == mav::camera_cap_has_basic_zoom) == camera.basic_zoom);
            CHECK(std::isnan(cam.focal_length) == !camera.focal_length_mm.has_value());
            if (camera.focal_length_mm) CHECK(cam.focal_length == Approx(*camera.focal_length_mm));
            CHECK(cam.resolution_h == camera.width_px.value_or(0));
            CHECK(cam.resolution_v == camera.height_px.value_or(0));
            if (camera.sensor_width_mm) CHECK(cam.sensor_size_h == Approx(*camera.sensor_width_mm));
            if (camera.sensor_height_mm)
                CHECK(cam.sensor_size_v == Approx(*camera.sensor_height_mm));
        }
}

TEST_CASE("capability names: what STATE `capabilities.features` lists") {
    CHECK(capabilities_of("orion").names() ==
          std::vector<std::string>{"point_angles", "rate", "geopoint", "zoom"});
    CHECK(capabilities_of("viewpro").names() == std::vector<std::string>{"point_angles"});
}

TEST_CASE("firmware from the version packets") {
    json s = orion_state();
    CHECK_FALSE(capabilities_of("orion").identity(s).firmware);
    s["versions"] = {{"crown", {{"version", "4.2.1"}, {"part_number", "x"}}}};
    CHECK(capabilities_of("orion").identity(s).firmware == "4.2.1");
}
