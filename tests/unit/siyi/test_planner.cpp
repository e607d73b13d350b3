// The SIYI planner and steering: catalogue parameters in, SIYI messages out - angles negated
// into SIYI's left-positive yaw, speeds scaled to the model's top rate, zoom within the
// model's range, and geopoint/path aimed by gimbald from the vehicle's position.
#include <catch2/catch.hpp>

#include "protocols/siyi/codec/messages.hpp"
#include "protocols/siyi/siyi_commands.hpp"
#include "vectors.hpp"

using namespace gimbal;
using namespace gimbal::protocols;
using nlohmann::json;

namespace {

SiyiCommandContext context(bool fix = false, siyi::Model model = siyi::Model::zt30) {
    SiyiCommandContext c;
    c.now_s = 10.0;
    c.has_vehicle_fix = fix;
    if (fix) c.vehicle_yaw_deg = 0.0;
    c.model = &siyi::model_info(model);
    return c;
}

vehicle::AircraftFix fix_north() {
    vehicle::AircraftFix f;
    f.lat_deg = 45.7;
    f.lon_deg = -121.5;
    f.alt_msl_m = 500;
    return f;
}

template <class M>
M only(const SiyiPlan& p) {
    REQUIRE(p.send.size() == 1);
    const auto* m = std::get_if<M>(&p.send[0]);
    REQUIRE(m);
    return *m;
}

}  // namespace

TEST_CASE("planner: position sends 0x0E with SIYI's yaw", "[siyi][planner]") {
    const auto p = plan_siyi_command("position", {{"pan", 30}, {"tilt", -45}}, context());
    REQUIRE(p);
    const auto m = only<siyi::SetGimbalAttitude>(*p);
    CHECK(m.yaw == Approx(-30));
    CHECK(m.pitch == Approx(-45));
    REQUIRE(p->hold);
    CHECK(std::holds_alternative<std::monostate>(*p->hold));
}

TEST_CASE("planner: center is the SDK's one-key centering and lets go of a held target",
          "[siyi][planner]") {
    const auto p = plan_siyi_command("center", json::object(), context(true));
    REQUIRE(p);
    const auto m = only<siyi::Center>(*p);
    CHECK(m.position == siyi::CenterPosition::one_key_center);
    // The SDK's own example frame (CTRL 01, SEQ 0).
    CHECK(siyi::encode(siyi::ToGimbal{m}, siyi::Header{}) == siyi_test::sdk_requests()[10].bytes);
    REQUIRE(p->hold);
    CHECK(std::holds_alternative<std::monostate>(*p->hold));
    const auto refused = plan_siyi_command("center", {{"pan", 0}}, context());
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code == command::ErrorCode::bad_request);
}

TEST_CASE("planner: stabilized position needs the heading and holds it", "[siyi][planner]") {
    const json r = {{"pan", 10}, {"tilt", 0}, {"stabilized", true}};
    const auto refused = plan_siyi_command("position", r, context(false));
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code == command::ErrorCode::unavailable);
    const auto p = plan_siyi_command("position", r, context(true));
    REQUIRE(p);
    SiyiSteering steering;
    steering.hold(*p->hold);
    vehicle::AircraftFix f = fix_north();
    f.yaw_deg = 40;  // the aircraft turned right: the pan goes left
    const auto m = steering.command(f, std::nullopt, std::nullopt, 11.0);
    REQUIRE(m);
    CHECK(std::get<siyi::SetGimbalAttitude>(*m).yaw == Approx(30));  // pan -30
}

TEST_CASE("planner: rate scales to the model's top rate, and an impulse stops", "[siyi][planner]") {
    const auto& zt30 = siyi::model_info(siyi::Model::zt30);
    const json r = {
        {"pan", zt30.max_rate_dps / 2}, {"tilt", -zt30.max_rate_dps * 2}, {"impulse_time_s", 0.5}};
    const auto p = plan_siyi_command("rate", r, context());
    REQUIRE(p);
    const auto m = only<siyi::GimbalRotation>(*p);
    CHECK(m.turn_yaw == 50);      // right positive, as gimbald's pan
    CHECK(m.turn_pitch == -100);  // saturated
    SiyiSteering steering;
    steering.hold(*p->hold);
    CHECK_FALSE(steering.command(std::nullopt, std::nullopt, std::nullopt, 10.2));
    const auto stop = steering.command(std::nullopt, std::nullopt, std::nullopt, 10.6);
    REQUIRE(stop);
    CHECK(std::get<siyi::GimbalRotation>(*stop).turn_yaw == 0);
    CHECK_FALSE(steering.command(std::nullopt, std::nullopt, std::nullopt, 10.7));  // once
}

TEST_CASE("planner: camera_zoom within the model's range", "[siyi][planner]") {
    const auto p = plan_siyi_command("camera_zoom", {{"zoom", 4.5}}, context());
    REQUIRE(p);
    CHECK(only<siyi::AbsoluteZoom>(*p).zoom == Approx(4.5));
    CHECK_FALSE(p->hold);  // zoom keeps what the gimbal is held to
    const auto& a8 = siyi::model_info(siyi::Model::a8_mini);
    const auto beyond = plan_siyi_command("camera_zoom", {{"zoom", a8.zoom_max + 1}},
                                          context(false, siyi::Model::a8_mini));
    REQUIRE_FALSE(beyond);
    CHECK(beyond.error().code == command::ErrorCode::out_of_range);
    CHECK_FALSE(plan_siyi_command("camera_zoom", {{"zoom", 2}, {"index", 1}}, context()));
    CHECK_FALSE(plan_siyi_command("camera_zoom", {{"zoom", 2}, {"focus", 1}}, context()));
    CHECK(plan_siyi_command("camera_zoom", {{"zoom", 2}, {"focus", -1}}, context()));
}

TEST_CASE("planner: catalogue ranges and unknown keys are the catalogue's", "[siyi][planner]") {
    const auto p = plan_siyi_command("position", {{"pan", 181}, {"tilt", 0}}, context());
    REQUIRE_FALSE(p);
    CHECK(p.error().message.find("'pan'") != std::string::npos);
    CHECK_FALSE(plan_siyi_command("rate", {{"pan", 1}, {"tilt", 0}, {"bogus", 1}}, context()));
    CHECK_FALSE(plan_siyi_command("laser", json::object(), context()));
}

TEST_CASE("planner: geopoint is aimed by gimbald from the vehicle", "[siyi][planner]") {
    const json r = {{"lat", 45.7}, {"lon", -121.49}, {"alt", 0}};
    const auto refused = plan_siyi_command("geopoint", r, context(false));
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code == command::ErrorCode::unavailable);
    const auto p = plan_siyi_command("geopoint", r, context(true));
    REQUIRE(p);
    CHECK(p->send.empty());
    SiyiSteering steering;
    steering.hold(*p->hold);
    const vehicle::AircraftFix f = fix_north();
    const geo::Lla camera{f.lat_deg, f.lon_deg, f.alt_msl_m};
    const auto m = steering.command(f, camera, std::nullopt, 10.0);
    REQUIRE(m);
    const auto& a = std::get<siyi::SetGimbalAttitude>(*m);
    CHECK(a.yaw == Approx(-90).margin(0.5));  // east, to the right: SIYI yaw negative
    CHECK(a.pitch < -30);
    CHECK(a.pitch > -60);
    CHECK_FALSE(steering.command(std::nullopt, camera, std::nullopt, 10.0));  // no fix
}

TEST_CASE("planner: path down, and a path swept from the vehicle", "[siyi][planner]") {
    const auto down = plan_siyi_command("path", {{"down", true}}, context());
    REQUIRE(down);
    CHECK(only<siyi::SetGimbalAttitude>(*down).pitch == Approx(-90));
    const json r = {{"points", json::array({{{"lat", 45.71}, {"lon", -121.5}, {"alt", 0}},
                                            {{"lat", 45.72}, {"lon", -121.5}, {"alt", 0}}})}};
    CHECK_FALSE(plan_siyi_command("path", r, context(false)));
    const auto p = plan_siyi_command("path", r, context(true));
    REQUIRE(p);
    SiyiSteering steering;
    steering.hold(*p->hold);
    const vehicle::AircraftFix f = fix_north();
    const auto m =
        steering.command(f, geo::Lla{f.lat_deg, f.lon_deg, f.alt_msl_m}, std::nullopt, 10.1);
    REQUIRE(m);
    CHECK(std::get<siyi::SetGimbalAttitude>(*m).yaw == Approx(0).margin(1));  // ahead, north
}
