// STATE `siyi` and the shared `telemetry` from what a SIYI camera reports: gimbald's frame
// (pan is the negated SIYI yaw), the model from the hardware id, fields of view per model and
// zoom, the line of sight on the ground with the vehicle's fix, and staleness.
#include <catch2/catch.hpp>

#include "protocols/siyi/siyi_capabilities.hpp"
#include "protocols/siyi/siyi_state.hpp"

using namespace gimbal;
using namespace gimbal::protocols;
using nlohmann::json;

namespace {

json snapshot(const SiyiState& s, double now_s) {
    json out = json::object();
    state::JsonWriter w(out);
    s.write(w, now_s);
    return out;
}

siyi::GimbalAttitude attitude(double yaw, double pitch) {
    siyi::GimbalAttitude a;
    a.yaw = yaw;
    a.pitch = pitch;
    a.yaw_rate = 5;
    return a;
}

vehicle::AircraftFix level_north(double alt_msl_m = 100) {
    vehicle::AircraftFix f;
    f.lat_deg = 45.7;
    f.lon_deg = -121.5;
    f.alt_msl_m = alt_msl_m;
    return f;
}

}  // namespace

TEST_CASE("state: nothing reported is null, and stale", "[siyi][state]") {
    SiyiState s{SiyiOptions{}};
    const json j = snapshot(s, 1.0);
    CHECK(j["siyi"]["hardware_id"].is_null());
    CHECK(j["siyi"]["model"].is_null());
    CHECK(j["siyi"]["attitude"].is_null());
    CHECK(j["telemetry"].is_null());
    CHECK(s.stale(1.0));
    CHECK_FALSE(s.telemetry_age_s(1.0));
}

TEST_CASE("state: attitude in gimbald's frame, telemetry's pan/tilt and field of view",
          "[siyi][state]") {
    SiyiState s{SiyiOptions{}};
    s.apply(attitude(10, -20), 2.0);  // SIYI yaw 10: ten degrees LEFT
    const json j = snapshot(s, 2.5);
    // STATE siyi: as the camera reports it (contract section 22), yaw left positive.
    CHECK(j["siyi"]["attitude"]["yaw"] == Approx(10));
    CHECK(j["siyi"]["attitude"]["pitch"] == Approx(-20));
    CHECK(j["siyi"]["attitude_rate"]["yaw"] == Approx(5));
    CHECK(j["siyi"]["age_s"] == Approx(0.5));
    REQUIRE(s.telemetry());
    CHECK(*s.telemetry()->pan == Approx(-10));
    CHECK(*s.telemetry()->tilt == Approx(-20));
    // No model reported yet: the ZT30's table, at zoom 1.
    const auto fov = siyi::field_of_view(siyi::Model::zt30, 1.0);
    CHECK(*s.telemetry()->hfov == Approx(fov.hfov_deg).margin(1e-4));
    CHECK(*s.telemetry()->vfov == Approx(fov.vfov_deg).margin(1e-4));
    CHECK_FALSE(s.telemetry()->lat);  // no vehicle fix: no position
    CHECK_FALSE(s.stale(2.5));
    CHECK(s.telemetry_count() == 1);
}

TEST_CASE("state: the hardware id names the model, zoom narrows the view", "[siyi][state]") {
    SiyiState s{SiyiOptions{}};
    const auto& a8 = siyi::model_info(siyi::Model::a8_mini);
    s.apply(siyi::HardwareId{std::string(a8.id_prefix) + "12345678"}, 1.0);
    s.apply(siyi::CurrentZoom{4.0}, 1.0);
    s.apply(attitude(0, 0), 1.0);
    CHECK(s.data().model == siyi::Model::a8_mini);
    const json j = snapshot(s, 1.0);
    CHECK(j["siyi"]["model"] == "A8 mini");
    CHECK(j["siyi"]["hardware_id"] == std::string(a8.id_prefix) + "12345678");
    CHECK(j["siyi"]["zoom"] == Approx(4.0));
    const auto fov = siyi::field_of_view(siyi::Model::a8_mini, 4.0);
    CHECK(*s.telemetry()->hfov == Approx(fov.hfov_deg).margin(1e-4));

    // A configured model wins over the id.
    SiyiOptions o;
    o.model = SiyiModelSetting::zr30;
    SiyiState configured{o};
    configured.apply(siyi::HardwareId{std::string(a8.id_prefix) + "12345678"}, 1.0);
    CHECK(configured.data().model == siyi::Model::zr30);
}

TEST_CASE("state: firmware, recording and the laser", "[siyi][state]") {
    SiyiState s{SiyiOptions{}};
    s.apply(siyi::FirmwareVersion{0x6E030203, 0x00010502, 0}, 1.0);
    s.apply(siyi::CameraSystemInfo{}, 1.0);
    s.apply(siyi::FunctionFeedback{siyi::FeedbackInfo::record_started}, 1.0);
    s.apply(siyi::LaserDistance{0}, 1.0);  // out of range
    json j = snapshot(s, 1.0);
    CHECK(j["siyi"]["firmware"]["camera"] == "3.2.3");
    CHECK(j["siyi"]["firmware"]["gimbal"] == "1.5.2");
    CHECK(j["siyi"]["firmware"]["zoom"].is_null());
    CHECK(j["siyi"]["recording"] == true);
    CHECK(j["siyi"]["record_status"] == "recording");
    CHECK(j["siyi"]["laser_range_m"].is_null());
    s.apply(siyi::LaserDistance{123.4}, 1.0);
    s.apply(siyi::FunctionFeedback{siyi::FeedbackInfo::record_stopped}, 1.0);
    j = snapshot(s, 1.0);
    CHECK(j["siyi"]["laser_range_m"] == Approx(123.4));
    CHECK(j["siyi"]["recording"] == false);
    CHECK(j["siyi"]["record_status"] == "off");
}

TEST_CASE("state: with the vehicle's fix, the line of sight meets the flat ground",
          "[siyi][state]") {
    SiyiOptions o;
    o.geoid_undulation_m = 0;
    o.ground_alt_m = 0;
    SiyiState s{o};
    s.set_vehicle(level_north(100));
    s.apply(attitude(0, -90), 1.0);  // straight down
    const auto* t = &*s.telemetry();
    REQUIRE(t->lat);
    CHECK(*t->lat == Approx(45.7));
    CHECK(*t->alt == Approx(100));
    REQUIRE(t->target);
    CHECK(t->target->lat == Approx(45.7).margin(1e-5));
    CHECK(t->target->lon == Approx(-121.5).margin(1e-5));
    CHECK(t->target->alt == Approx(0).margin(0.01));
    CHECK(t->view.footprint);

    // Looking 45 degrees down to the right (east, the aircraft heading north).
    s.apply(attitude(-90, -45), 1.1);
    t = &*s.telemetry();
    REQUIRE(t->target);
    CHECK(t->target->lon > -121.5);
    CHECK(t->target->lat == Approx(45.7).margin(1e-4));

    SiyiCapabilities caps(s.data());
    REQUIRE(caps.image());
    CHECK(caps.line_of_sight());
}

TEST_CASE("state: a lost event once the attitude goes stale", "[siyi][state]") {
    SiyiOptions o;
    o.stale_after_s = 1.0;
    SiyiState s{o};
    s.apply(attitude(0, 0), 1.0);
    std::vector<state::Event> events;
    s.tick(1.5, events);
    CHECK(events.empty());
    s.tick(2.5, events);
    s.tick(3.0, events);
    REQUIRE(events.size() == 1);
    CHECK(events[0].kind == "lost");
}

TEST_CASE("capabilities: limits in gimbald's frame, zoom as a ratio", "[siyi][state]") {
    SiyiOptions o;
    o.model = SiyiModelSetting::a8mini;
    SiyiState s{o};
    SiyiCapabilities caps(s.data());
    const auto& m = siyi::model_info(siyi::Model::a8_mini);
    const auto l = caps.limits();
    CHECK(*l.pan_min_deg == Approx(-m.yaw_max));
    CHECK(*l.pan_max_deg == Approx(-m.yaw_min));
    CHECK(*l.tilt_min_deg == Approx(m.pitch_min));
    const auto z = caps.zoom({session::ZoomKind::range_percent, 100});
    REQUIRE(z);
    CHECK((*z)["cmd"] == "camera_zoom");
    CHECK((*z)["zoom"] == Approx(m.zoom_max));
    CHECK(caps.identity().model == "A8 mini");
    CHECK(caps.features().geopoint);
}
