// Typed capabilities (session/capabilities.hpp) of every protocol, checked against what the
// MAVLink gimbal manager (lib/gimbal_protocol) does with them, over a grid of commands and
// typed states (with and without what the gimbal reports): the same requests, the same
// refusals (unsupported / not yet), the same line of sight, view, limits, identity and camera.
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

// The single-gimbal manager the mapping runs, and its state.
struct One {
    std::string name, protocol;
    AnyGimbal state;
    const caps::Capabilities& capabilities() const { return state->capabilities(); }
};

std::vector<One> gimbals(bool with_data) {
    if (!with_data) return {{"main", "orion", empty_orion()}, {"nose", "viewpro", empty_viewpro()}};
    return {{"main", "orion", orion_state()}, {"nose", "viewpro", viewpro_state()}};
}

Mapped old_mapping(const One& g, const gimbal::mavlink::Payload& payload, const VehicleView& v) {
    GimbalManager m(expose({{g.name, g.protocol}}));
    return m.message(payload, gcs, v, [&](const std::string&) { return g.state->view(); });
}

Mapped old_command(const One& g, const CommandView& c, const VehicleView& v) {
    GimbalManager m(expose({{g.name, g.protocol}}));
    return m.command(
        c, gcs, v, [&](const std::string&) { return g.state->view(); }, 0);
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
                                const auto& c = g.capabilities();
                                if (!std::isnan(pitch) || !std::isnan(yaw)) {
                                    caps::AnglesTarget t;
                                    t.pitch_deg = deg(py.pitch);
                                    t.yaw_deg = deg(py.yaw);
                                    t.yaw_frame =
                                        flags ? caps::YawFrame::earth : caps::YawFrame::vehicle;
                                    t.vehicle_heading_deg = heading;
                                    same(old, c.point_angles(t));
                                } else if (!std::isnan(rate)) {
                                    same(old, c.rate({py.pitch_rate * rad_to_deg,
                                                      py.yaw_rate * rad_to_deg}));
                                }
                            }
}

TEST_CASE("absolute_angles: complete angles and rates read nothing of the gimbal's state") {
    // A gimbal that claims this answers the same with nothing reported yet.
    struct Pair {
        std::string protocol;
        AnyGimbal state, empty;
    };
    const std::vector<Pair> states = {{"orion", orion_state(), empty_orion()},
                                      {"viewpro", viewpro_state(), empty_viewpro()},
                                      {"mavlink", device_state(), empty_device()}};
    int claimed = 0;
    for (const auto& [protocol, state, empty] : states) {
        const auto& c = state->capabilities();
        const auto& nothing = empty->capabilities();
        INFO(protocol);
        CHECK(c.features().absolute_angles == protocols::find(protocol)->features.absolute_angles);
        if (!c.features().absolute_angles) {
            // A gimbal stepped from where it looks now cannot do without its state.
            CHECK_FALSE(nothing.point_angles({-10.0, 20.0, caps::YawFrame::vehicle, 100.0}).ok());
            continue;
        }
        ++claimed;
        for (const auto frame : {caps::YawFrame::vehicle, caps::YawFrame::earth})
            for (const double pitch : {-90.0, -10.5, 30.0})
                for (const double yaw : {-170.0, 0.0, 95.25}) {
                    const caps::AnglesTarget t{pitch, yaw, frame, 100.0};
                    const auto with = c.point_angles(t);
                    const auto without = nothing.point_angles(t);
                    REQUIRE(with.ok() == without.ok());
                    if (with.ok()) CHECK(with.value() == without.value());
                }
        const caps::RateTarget r{5.0, -3.0};
        CHECK(c.rate(r).ok() == nothing.rate(r).ok());
        if (c.rate(r).ok()) CHECK(c.rate(r).value() == nothing.rate(r).value());
    }
    CHECK(claimed == 2);  // the Orion and the MAVLink device take absolute angles
}

TEST_CASE("geopoint and stop: DO_SET_ROI_LOCATION and DO_SET_ROI_NONE, per protocol") {
    for (const auto& g : gimbals(true)) {
        INFO(g.protocol);
        const auto& c = g.capabilities();
        const Mapped roi =
            old_command(g,
                        int_cmd(mav::mav_cmd::do_set_roi_location, {1, 0, 0, 0}, 473977420,
                                85455940, 488.5f, mav::mav_frame::global_int),
                        vehicle());
        same(roi, c.geopoint({47.397742, 8.545594, 488.5}));
        const Mapped none = old_command(
            g, long_cmd(mav::mav_cmd::do_set_roi_none, {1, 0, 0, 0, 0, 0, 0}), vehicle());
        same(none, c.stop());
        CHECK(c.features().geopoint == !roi.requests.empty());
        CHECK(protocols::find(g.protocol)->features.geopoint == c.features().geopoint);
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
                same(old, g.capabilities().zoom(t));
            }
}

TEST_CASE("line of sight, view, identity, limits and camera: the manager's status messages") {
    for (const bool with_data : {true, false})
        for (const auto& g : gimbals(with_data)) {
            INFO(g.protocol << " data " << with_data);
            const auto& c = g.capabilities();
            const ExposedGimbal exposed{g.name, g.protocol, 1};
            const gimbal::session::GimbalView view = g.state->view();

            const auto old_los = line_of_sight(view);
            const auto los = c.line_of_sight();
            REQUIRE(old_los.has_value() == los.has_value());
            if (los) {
                CHECK(los->w == Approx(old_los->w));
                CHECK(los->x == Approx(old_los->x));
                CHECK(los->y == Approx(old_los->y));
                CHECK(los->z == Approx(old_los->z));
            }

            const auto fov = fov_status(exposed, view, 0);
            const auto v = c.view();
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

            const auto info = device_information(exposed, view, 0);
            const auto id = c.identity();
            const auto text = [](const auto& bytes) {
                return std::string(reinterpret_cast<const char*>(bytes.data()));
            };
            CHECK(text(info.vendor_name) == id.vendor);
            CHECK(text(info.model_name) == id.model);
            const auto l = c.limits();
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

            const auto cam = camera_information(exposed, view, 0);
            const auto camera = c.camera();
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
    const auto names = [](const std::string& protocol) {
        return caps::feature_names(protocols::find(protocol)->features);
    };
    CHECK(names("orion") == std::vector<std::string>{"point_angles", "rate", "geopoint", "zoom"});
    CHECK(names("viewpro") == std::vector<std::string>{"point_angles"});
    CHECK(orion_state()->capabilities().names() == names("orion"));
    CHECK(viewpro_state()->capabilities().names() == names("viewpro"));
    CHECK(device_state()->capabilities().names() == names("mavlink"));
}

TEST_CASE("firmware from the version packets") {
    const auto s = orion_state();
    CHECK_FALSE(s->capabilities().identity().firmware);
    gimbal::orion::CrownVersion crown;
    crown.version = "4.2.1";
    crown.part_number = "x";
    s->data.packets.crown_version =
        gimbal::state::Received<gimbal::orion::CrownVersion>{crown, nullptr, 0};
    CHECK(s->capabilities().identity().firmware == "4.2.1");
}
