// The Orion's command options on a MAVLink gimbal device (contract sections 4 and 19):
// `stabilized` on position and rate (held in the earth frame: the set-attitude's quaternion
// and GIMBAL_DEVICE_FLAGS, and the simulated device closing the loop while the aircraft
// turns), geopoint's `stare` (stare_start once the line of sight is on the point),
// `joystick_range_m` refused, and the geoid undulation the session uses.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "device_fixtures.hpp"
#include "geo/wgs84.hpp"
#include "protocols/mavlink_device/mavlink_device_options.hpp"
#include "protocols/mavlink_device/mavlink_device_sim.hpp"
#include "protocols/mavlink_device/mavlink_device_stare.hpp"
#include "protocols/registry.hpp"

using namespace gimbal;
using namespace device_fixtures;
using nlohmann::json;
using protocols::MavlinkDeviceOptions;
using protocols::MavlinkDeviceProtocol;

namespace {

// GIMBAL_DEVICE_FLAGS and GIMBAL_DEVICE_CAP_FLAGS (common.xml).
constexpr std::uint16_t roll_lock = 4, pitch_lock = 8, yaw_lock = 16, in_vehicle = 32,
                        in_earth = 64;
constexpr std::uint32_t cap_axes = 32 | 256, cap_yaw_lock = 1024, cap_earth = 4096;

std::vector<std::uint8_t> information(std::uint32_t cap_flags) {
    mavlink::GimbalDeviceInformation i;
    i.cap_flags = static_cast<std::uint16_t>(cap_flags);
    return device_frame(i);
}

// The last set-attitude a steering tick sends.
std::optional<mavlink::GimbalDeviceSetAttitude> steered(MavlinkDeviceProtocol& p,
                                                        const vehicle::VehicleState& v,
                                                        double now_s) {
    std::vector<session::Bytes> out;
    p.steer(v, now_s, now_s, out);
    std::optional<mavlink::GimbalDeviceSetAttitude> last;
    for (const auto& m : decode(out))
        if (const auto* s = std::get_if<mavlink::GimbalDeviceSetAttitude>(&m.payload)) last = *s;
    return last;
}

// common.xml's quaternion for roll 0, pitch `tilt`, yaw `yaw`: qz(yaw) * qy(tilt).
void check_quaternion(const std::array<float, 4>& q, double yaw, double tilt) {
    INFO("yaw " << yaw << " tilt " << tilt);
    const double cy = std::cos(yaw * deg / 2), sy = std::sin(yaw * deg / 2);
    const double cp = std::cos(tilt * deg / 2), sp = std::sin(tilt * deg / 2);
    CHECK(q[0] == Approx(cy * cp).margin(1e-6));
    CHECK(q[1] == Approx(-sy * sp).margin(1e-6));
    CHECK(q[2] == Approx(cy * sp).margin(1e-6));
    CHECK(q[3] == Approx(sy * cp).margin(1e-6));
}

std::vector<state::Event> receive_events(MavlinkDeviceProtocol& p,
                                         const std::vector<std::uint8_t>& bytes, double now_s) {
    std::vector<state::Event> events;
    std::vector<session::Bytes> replies;
    p.receive(bytes, now_s, events, replies);
    return events;
}

// The device's line of sight: its yaw from north (degrees), from its state.
double sight_yaw(const MavlinkDeviceProtocol& p) {
    const auto los = p.capabilities().line_of_sight();
    REQUIRE(los);
    return geo::quat_to_euler(*los).yaw_deg;
}

// The simulated device in the loop: the aircraft at `aircraft(t)`, steering and feed at
// 20 Hz, the device's reports at 20 Hz; `each(t)` after every report.
template <class AircraftAt, class Each>
void fly(MavlinkDeviceProtocol& p, protocols::MavlinkDeviceSim& sim, vehicle::VehicleState& v,
         double from_s, double to_s, AircraftAt aircraft, Each each) {
    for (double t = from_s; t < to_s - 1e-9; t += 0.05) {
        report(v, aircraft(t), t);
        std::vector<session::Bytes> out;
        p.steer(v, t, t, out);
        for (const auto& b : out) sim.receive(b, t);
        std::vector<std::uint8_t> bytes;
        sim.advance(t + 0.05, bytes);
        each(t + 0.05, receive_events(p, bytes, t + 0.05));
    }
}

void connect(MavlinkDeviceProtocol& p, protocols::MavlinkDeviceSim& sim) {
    for (const auto& b : p.on_connect()) sim.receive(b, 0.0);
    std::vector<std::uint8_t> bytes;
    sim.advance(0.05, bytes);
    receive(p, bytes, 0.05);
    REQUIRE(p.state().has_information());
}

// The session, the simulated device and the aircraft's vehicle state, connected.
struct Loop {
    explicit Loop(MavlinkDeviceOptions options = {}) : p(std::move(options)) { connect(p, sim); }
    MavlinkDeviceProtocol p;
    protocols::MavlinkDeviceSim sim{protocols::MavlinkDeviceSimOptions{}};
    vehicle::VehicleState v{vehicle_fixtures::options()};
};

// The aircraft flying north at 40 m/s, 500 m up.
Aircraft flying_north(double t) {
    Aircraft a;
    a.lat = 45.7 + 40 * t / 111'000.0;
    a.yaw = 0;
    a.vn = 40;
    return a;
}

// The aircraft flying north (its fix at 0.1 s) given a path over 1.5 km of ground to the
// east of its track, in along-track steps of 5 degrees.
void start_stepped_path(Loop& loop) {
    report(loop.v, flying_north(0.1), 0.1);
    steered(loop.p, loop.v, 0.1);
    const json path = {{"points",
                        {{{"lat", 45.7}, {"lon", -121.49}, {"alt", 0}},
                         {{"lat", 45.7135}, {"lon", -121.49}, {"alt", 0}}}},
                       {"along_step_deg", 5}};
    command::Plan plan;
    REQUIRE_FALSE(loop.p.plan("path", path, {0.1, 1.79e9}, plan));
}

}  // namespace

TEST_CASE("position stabilized: the yaw from north is held while the aircraft turns") {
    vehicle::VehicleState v(vehicle_fixtures::options());
    Aircraft a;  // heading east
    a.yaw = 90;
    a.yaw_rate = 10;

    SECTION("a device with yaw in the earth frame: YAW_IN_EARTH_FRAME and YAW_LOCK") {
        MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
        receive(p, information(cap_axes | cap_yaw_lock | cap_earth), 0.5);
        report(v, a, 1.0);
        REQUIRE(steered(p, v, 1.0) == std::nullopt);  // nothing held yet
        const auto m =
            planned_attitude(p, "position", {{"pan", 30}, {"tilt", -20}, {"stabilized", true}});
        check_quaternion(m.q, 120, -20);  // heading 90 + pan 30
        CHECK(m.flags == (roll_lock | pitch_lock | yaw_lock | in_earth));
        // The aircraft turns to south-west: the set-point does not move.
        a.yaw = -135;
        report(v, a, 1.5);
        const auto later = steered(p, v, 1.5);
        REQUIRE(later);
        check_quaternion(later->q, 120, -20);
        CHECK(later->flags == (roll_lock | pitch_lock | yaw_lock | in_earth));
    }
    SECTION("an older device with yaw lock only: YAW_LOCK without a frame flag") {
        MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
        receive(p, information(cap_axes | cap_yaw_lock), 0.5);
        report(v, a, 1.0);
        steered(p, v, 1.0);
        const auto m =
            planned_attitude(p, "position", {{"pan", -100}, {"tilt", 5}, {"stabilized", true}});
        check_quaternion(m.q, -10, 5);
        CHECK(m.flags == (roll_lock | pitch_lock | yaw_lock));
        a.yaw = 0;
        report(v, a, 1.5);
        check_quaternion(steered(p, v, 1.5).value().q, -10, 5);
    }
    SECTION("a device that takes yaw from the nose only: gimbald turns it at every tick") {
        MavlinkDeviceProtocol p(MavlinkDeviceOptions{});  // no information: from the nose
        report(v, a, 1.0);
        steered(p, v, 1.0);
        const auto m =
            planned_attitude(p, "position", {{"pan", 30}, {"tilt", -20}, {"stabilized", true}});
        check_quaternion(m.q, 30, -20);
        CHECK(m.flags == (roll_lock | pitch_lock | in_vehicle));
        // Feed-forward: the aircraft's turn, against it.
        CHECK(m.angular_velocity_z == Approx(-10 * deg));
        a.yaw = 180;
        report(v, a, 1.5);
        const auto later = steered(p, v, 1.5).value();
        check_quaternion(later.q, -60, -20);  // still 120 from north
        CHECK(later.flags == (roll_lock | pitch_lock | in_vehicle));
    }
    SECTION("stabilized false stays in the vehicle frame") {
        MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
        receive(p, information(cap_axes | cap_earth), 0.5);
        report(v, a, 1.0);
        steered(p, v, 1.0);
        const auto m =
            planned_attitude(p, "position", {{"pan", 30}, {"tilt", -20}, {"stabilized", false}});
        check_quaternion(m.q, 30, -20);
        CHECK(m.flags == (roll_lock | pitch_lock | in_vehicle));
    }
}

TEST_CASE("position stabilized needs the vehicle's heading; refused, it changes nothing") {
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    planned_attitude(p, "position", {{"pan", 10}, {"tilt", -5}});
    command::Plan plan;
    const auto e =
        p.plan("position", {{"pan", 30}, {"tilt", 0}, {"stabilized", true}}, {1.0, 0}, plan);
    REQUIRE(e);
    CHECK(e->code == command::ErrorCode::unavailable);
    CHECK(e->message.find("stabilized") != std::string::npos);
    CHECK(plan.packets.empty());
    vehicle::VehicleState v(vehicle_fixtures::options());
    const auto still = steered(p, v, 1.1);
    REQUIRE(still);
    check_quaternion(still->q, 10, -5);
}

TEST_CASE("position stabilized on the simulated device: the camera keeps its direction") {
    // The aircraft turns at 15 deg/s for 12 s (180 degrees); the device's line of sight keeps
    // the heading at the command + 60 degrees from north.
    Loop loop;
    auto& [p, sim, v] = loop;
    const auto turning = [](double t) {
        Aircraft a;
        a.yaw = session::wrap180(15 * t);
        a.yaw_rate = 15;
        return a;
    };
    report(v, turning(0.1), 0.1);
    steered(p, v, 0.1);
    planned_attitude(p, "position", {{"pan", 60}, {"tilt", -30}, {"stabilized", true}}, 0.1);
    const double north = turning(0.1).yaw + 60;
    double worst = 0;
    fly(p, sim, v, 0.1, 12.0, turning, [&](double t, const auto&) {
        if (t > 2.0) worst = std::max(worst, std::abs(session::wrap180(sight_yaw(p) - north)));
    });
    INFO("worst yaw error " << worst);
    CHECK(worst < 1.0);
    // Unstabilized, the same pan turns with the aircraft.
    planned_attitude(p, "position", {{"pan", 60}, {"tilt", -30}}, 12.0);
    fly(p, sim, v, 12.0, 16.0, turning, [](double, const auto&) {});
    CHECK(session::wrap180(sight_yaw(p) - turning(16.0).yaw - 60) == Approx(0).margin(1.0));
}

TEST_CASE("rate: stabilized (the default) integrates from north, false from the nose") {
    vehicle::VehicleState v(vehicle_fixtures::options());
    Aircraft a;
    a.yaw_rate = 5;
    SECTION("earth frame device") {
        MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
        receive(p, information(cap_axes | cap_earth), 0.5);
        auto m = planned_attitude(p, "rate", {{"pan", 10}, {"tilt", -4}});
        CHECK(std::isnan(m.q[0]));
        CHECK(m.flags == (roll_lock | pitch_lock | yaw_lock | in_earth));
        CHECK(m.angular_velocity_z == Approx(10 * deg));
        CHECK(m.angular_velocity_y == Approx(-4 * deg));
        m = planned_attitude(p, "rate", {{"pan", 10}, {"tilt", -4}, {"stabilized", false}});
        CHECK(m.flags == (roll_lock | pitch_lock | in_vehicle));
        CHECK(m.angular_velocity_z == Approx(10 * deg));
    }
    SECTION("yaw lock only") {
        MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
        receive(p, information(cap_axes | cap_yaw_lock), 0.5);
        CHECK(planned_attitude(p, "rate", {{"pan", 10}, {"tilt", 0}}).flags ==
              (roll_lock | pitch_lock | yaw_lock));
    }
    SECTION("from the nose only: the aircraft's turn is taken off") {
        MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
        report(v, a, 1.0);
        steered(p, v, 1.0);
        auto m = planned_attitude(p, "rate", {{"pan", 10}, {"tilt", 0}});
        CHECK(m.flags == (roll_lock | pitch_lock | in_vehicle));
        CHECK(m.angular_velocity_z == Approx(5 * deg));
        m = planned_attitude(p, "rate", {{"pan", 10}, {"tilt", 0}, {"stabilized", false}});
        CHECK(m.angular_velocity_z == Approx(10 * deg));
    }
}

TEST_CASE("rate on the simulated device: stabilized 0 holds north, unstabilized follows") {
    Loop loop;
    auto& [p, sim, v] = loop;
    const auto turning = [](double t) {
        Aircraft a;
        a.yaw = session::wrap180(-20 * t);
        a.yaw_rate = -20;
        return a;
    };
    fly(p, sim, v, 0.1, 1.0, turning, [](double, const auto&) {});
    planned_attitude(p, "rate", {{"pan", 0}, {"tilt", 0}}, 1.0);
    fly(p, sim, v, 1.0, 1.5, turning, [](double, const auto&) {});
    const double held = sight_yaw(p);
    fly(p, sim, v, 1.5, 5.5, turning, [](double, const auto&) {});
    CHECK(session::wrap180(sight_yaw(p) - held) == Approx(0).margin(1.0));
    // Unstabilized the camera turns with the aircraft: 80 degrees in 4 s.
    planned_attitude(p, "rate", {{"pan", 0}, {"tilt", 0}, {"stabilized", false}}, 5.5);
    fly(p, sim, v, 5.5, 6.0, turning, [](double, const auto&) {});
    const double before = sight_yaw(p);
    fly(p, sim, v, 6.0, 10.0, turning, [](double, const auto&) {});
    CHECK(session::wrap180(sight_yaw(p) - before) == Approx(-80).margin(1.5));
}

TEST_CASE("geopoint stare: stare_start once the line of sight is on the point, not before") {
    // The aircraft circles 500 m above the point at 400 m; the device starts looking ahead
    // at the horizon, far off the point.
    const geo::Lla point{45.7, -121.5, 100};
    const auto circling = [&](double t) {
        const double ang = 30.0 / 400.0 * t;
        const geo::Vec3 offset{400 * std::cos(ang), 400 * std::sin(ang), -500};
        const auto lla =
            geo::ecef_to_lla(geo::lla_to_ecef(point) + geo::ned_to_ecef(offset, point));
        Aircraft a;
        a.lat = lla.lat_deg;
        a.lon = lla.lon_deg;
        a.alt_msl = lla.alt_m;
        a.vn = -30 * std::sin(ang);
        a.ve = 30 * std::cos(ang);
        a.yaw = std::atan2(a.ve, a.vn) / deg;
        a.yaw_rate = 30.0 / 400.0 / deg;
        return a;
    };
    protocols::MavlinkDeviceSimOptions so;
    so.slew_rate_dps = 30;  // a few seconds to get there
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    protocols::MavlinkDeviceSim sim(so);
    vehicle::VehicleState v(vehicle_fixtures::options());
    connect(p, sim);
    fly(p, sim, v, 0.1, 0.5, circling, [](double, const auto&) {});
    const json request = {{"lat", point.lat_deg},
                          {"lon", point.lon_deg},
                          {"alt", point.alt_m},
                          {"stare", true},
                          {"closure", true}};
    planned_attitude(p, "geopoint", request, 0.5);
    CHECK(p.snapshot(0.5)["stare"].is_null());

    std::vector<json> starts;
    double first_on_s = -1, stare_s = -1, off_target_min = 180;
    fly(p, sim, v, 0.5, 20.0, circling, [&](double t, const std::vector<state::Event>& events) {
        const double error =
            protocols::pointing_error_deg(point, *p.state().camera(), *p.state().line_of_sight());
        for (const auto& e : events) {
            REQUIRE(e.kind == "stare_start");
            starts.push_back(e.fields);
            stare_s = t;
        }
        if (error <= protocols::stare_tolerance_deg && first_on_s < 0) first_on_s = t;
        if (stare_s < 0) off_target_min = std::min(off_target_min, error);
    });
    INFO("on target at " << first_on_s << " s, stare_start at " << stare_s << " s");
    REQUIRE(starts.size() == 1);  // once per command, though it stays on target
    CHECK(stare_s > 1.0);         // it took the slew
    CHECK(stare_s == Approx(first_on_s));
    CHECK(off_target_min > protocols::stare_tolerance_deg);
    const json& s = starts[0];
    INFO(s.dump());
    CHECK(s["lat"].get<double>() == Approx(point.lat_deg).margin(1e-6));
    CHECK(s["lon"].get<double>() == Approx(point.lon_deg).margin(1e-6));
    CHECK(s["alt"].get<double>() == Approx(100).margin(0.01));  // geoid 0: MSL = ellipsoid
    CHECK(s["gimbal_data_valid"] == true);
    CHECK(s["stare_started_by_time"] == false);
    CHECK(s["system_time_ms"].get<std::uint32_t>() > 0);
    const geo::Lla gimbal{s["gimbal_lat"].get<double>(), s["gimbal_lon"].get<double>(),
                          s["gimbal_alt"].get<double>()};
    CHECK(geo::norm(geo::lla_to_ecef(gimbal) - geo::lla_to_ecef(point)) ==
          Approx(std::hypot(400, 500)).margin(2));
    CHECK(s["slant_range"].get<double>() == Approx(std::hypot(400, 500)).margin(2));
    CHECK(s["tilt"].get<double>() == Approx(-std::atan2(500, 400) / deg).margin(1));
    CHECK(s["gimbal_quat"].size() == 4);
    CHECK(s["pan"].is_number());
    CHECK(p.snapshot(20.0)["stare"] == s);  // STATE stare: the latest, as for an Orion

    // A new geopoint with stare is a new stare; without stare, none.
    planned_attitude(p, "geopoint", request, 20.0);
    std::size_t more = 0;
    fly(p, sim, v, 20.0, 22.0, circling,
        [&](double, const std::vector<state::Event>& events) { more += events.size(); });
    CHECK(more == 1);
    planned_attitude(p, "geopoint", {{"lat", point.lat_deg}, {"lon", point.lon_deg}, {"alt", 0}},
                     22.0);
    more = 0;
    fly(p, sim, v, 22.0, 26.0, circling,
        [&](double, const std::vector<state::Event>& events) { more += events.size(); });
    CHECK(more == 0);
}

TEST_CASE("geopoint joystick_range_m: no joystick on a device link, refused, nothing changes") {
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    vehicle::VehicleState v(vehicle_fixtures::options());
    report(v, Aircraft{}, 1.0);
    steered(p, v, 1.0);
    planned_attitude(p, "position", {{"pan", 15}, {"tilt", -10}});
    command::Plan plan;
    const auto e =
        p.plan("geopoint", {{"lat", 45.7}, {"lon", -121.5}, {"alt", 0}, {"joystick_range_m", 500}},
               {1.0, 0}, plan);
    REQUIRE(e);
    CHECK(e->code == command::ErrorCode::bad_request);
    CHECK(e->message.find("joystick_range_m") != std::string::npos);
    CHECK(plan.packets.empty());
    const auto still = steered(p, v, 1.1);
    REQUIRE(still);
    check_quaternion(still->q, 15, -10);
    // 0 is the default and is taken.
    planned_attitude(p, "geopoint",
                     {{"lat", 45.7}, {"lon", -121.4}, {"alt", 0}, {"joystick_range_m", 0}});
}

TEST_CASE("geoid undulation: the geoid at the aircraft's position, or the configured one") {
    vehicle::VehicleState v(vehicle_fixtures::options());
    Aircraft a;
    a.alt_msl = 500;
    report(v, a, 1.0);
    const auto telemetry_of = [&](MavlinkDeviceProtocol& p) {
        std::vector<session::Bytes> out;
        p.steer(v, 1.0, 1.0, out);
        receive(p, device_frame(status(0, -45, 0, 32)), 1.0);
        return p.snapshot(1.0)["telemetry"];
    };
    std::vector<std::pair<double, double>> asked;
    MavlinkDeviceOptions o;
    o.geoid = [&](double lat, double lon) -> std::optional<double> {
        asked.emplace_back(lat, lon);
        return -21.25;
    };
    SECTION("not configured: the geoid model's, where the aircraft is") {
        MavlinkDeviceProtocol p(o);
        const auto t = telemetry_of(p);
        CHECK(t["geoid_undulation"].get<double>() == Approx(-21.25));
        CHECK(t["alt"].get<double>() == Approx(478.75));
        REQUIRE_FALSE(asked.empty());
        CHECK(asked.back().first == Approx(45.7));
        CHECK(asked.back().second == Approx(-121.5));
        // alt_ref msl converts with it.
        command::Plan plan;
        REQUIRE_FALSE(p.plan("geopoint",
                             {{"lat", 45.71}, {"lon", -121.5}, {"alt", 100}, {"alt_ref", "msl"}},
                             {1.0, 0}, plan));
        const auto& held = std::get<protocols::HoldGeopoint>(p.steering().held());
        CHECK(held.point.alt_m == Approx(78.75));
    }
    SECTION("configured: a fixed override") {
        o.geoid_undulation_m = 5.0;
        MavlinkDeviceProtocol p(o);
        const auto t = telemetry_of(p);
        CHECK(t["geoid_undulation"].get<double>() == Approx(5));
        CHECK(t["alt"].get<double>() == Approx(505));
        CHECK(asked.empty());
    }
    SECTION("no grid: 0") {
        o.geoid = [](double, double) -> std::optional<double> { return std::nullopt; };
        MavlinkDeviceProtocol p(o);
        CHECK(telemetry_of(p)["geoid_undulation"].get<double>() == Approx(0));
    }
}

TEST_CASE("geoid_undulation_m: null (the default) asks the geoid, a number overrides") {
    const auto options = [](const json& mavlink) {
        return protocols::read_mavlink_device_options({{"mavlink", mavlink}});
    };
    CHECK_FALSE(options(json::object()).geoid_undulation_m);
    CHECK_FALSE(options({{"geoid_undulation_m", nullptr}}).geoid_undulation_m);
    CHECK(options({{"geoid_undulation_m", -30.5}}).geoid_undulation_m == -30.5);
    const auto* e = protocols::find("mavlink");
    REQUIRE(e);
    REQUIRE(e->needs_geoid);
    CHECK(e->needs_geoid({{"mavlink", {{"geoid_undulation_m", nullptr}}}}));
    CHECK_FALSE(e->needs_geoid({{"mavlink", {{"geoid_undulation_m", 0}}}}));
    // The settings' geoid reaches the session.
    protocols::SessionSettings settings;
    settings.geoid_undulation = [](double, double) -> std::optional<double> { return 12.5; };
    auto session = e->make_session(settings, {{"name", "cam"}, {"protocol", "mavlink"}});
    vehicle::VehicleState v(vehicle_fixtures::options());
    report(v, Aircraft{}, 1.0);
    std::vector<session::Bytes> out;
    session->steer(v, 1.0, 1.0, out);
    std::vector<state::Event> events;
    std::vector<session::Bytes> replies;
    session->receive(device_frame(status(0, -45, 0, 32)), 1.0, events, replies);
    CHECK(session->snapshot(1.0)["telemetry"]["geoid_undulation"].get<double>() == Approx(12.5));
}

TEST_CASE("path with step-stare: a stare_start at each station, with the Orion's flags") {
    // The aircraft flies north at 40 m/s, 500 m up; the path runs 1.5 km along the ground to
    // its east. Along-track steps of 5 degrees: the follower slews to a station, stares (its
    // stare time runs out: nobody acknowledges) and steps on.
    Loop loop;
    auto& [p, sim, v] = loop;
    start_stepped_path(loop);

    std::vector<json> stares;
    std::vector<double> at;
    fly(p, sim, v, 0.1, 20.0, flying_north, [&](double t, const std::vector<state::Event>& events) {
        for (const auto& e : events) {
            if (e.kind != "stare_start") continue;
            stares.push_back(e.fields);
            at.push_back(t);
        }
    });
    INFO(stares.size() << " stares");
    REQUIRE(stares.size() >= 3);
    for (std::size_t i = 0; i < stares.size(); ++i) {
        const auto& s = stares[i];
        INFO(s.dump());
        CHECK(s["along_track_stare"] == true);
        CHECK(s["gimbal_data_valid"] == true);
        CHECK(s["lon"].get<double>() == Approx(-121.49).margin(1e-6));
        CHECK(s["lat"].get<double>() >= 45.7 - 1e-6);
        CHECK(s["lat"].get<double>() <= 45.7135 + 1e-6);
        CHECK(s["max_stare_time_s"].get<double>() > 0);
        CHECK(s["slant_range"].get<double>() > 500);
        if (i > 0) {
            CHECK(s["lat"].get<double>() > stares[i - 1]["lat"].get<double>());  // stepping on
            CHECK(at[i] - at[i - 1] >= 0.9 * s["prev_stare_time_s"].get<double>());
        }
    }
    // STATE `stare` holds the latest.
    CHECK(p.snapshot(20.0)["stare"] == stares.back());
}

TEST_CASE("stare_ack ends a path's stare when it echoes the stare's system_time_ms") {
    // `ack(fields)`: what is sent back at each stare_start (nullopt: nothing).
    const auto run = [&](auto ack, bool auto_ack = false) {
        MavlinkDeviceOptions options;
        options.auto_ack_stare = auto_ack;
        Loop loop(options);
        auto& [p, sim, v] = loop;
        start_stepped_path(loop);
        std::vector<json> stares;
        fly(p, sim, v, 0.1, 12.0, flying_north,
            [&](double t, const std::vector<state::Event>& events) {
                for (const auto& e : events) {
                    if (e.kind != "stare_start") continue;
                    stares.push_back(e.fields);
                    if (const std::optional<json> reply = ack(e.fields)) {
                        command::Plan acked;
                        const auto error = p.plan("stare_ack", *reply, {t, 1.79e9}, acked);
                        INFO((error ? error->message : "ok"));
                        CHECK_FALSE(error);
                        CHECK(acked.packets.empty());  // nothing goes to the device
                    }
                }
            });
        return stares;
    };
    const auto no_ack = [](const json&) { return std::optional<json>(); };
    const auto matching = [](const json& s) {
        return std::optional<json>(json{{"system_time_ms", s["system_time_ms"]}});
    };
    const auto wrong = [](const json& s) {
        return std::optional<json>(
            json{{"system_time_ms", s["system_time_ms"].get<std::uint32_t>() + 1}});
    };
    const auto unacked = run(no_ack);
    const auto acked = run(matching);
    const auto mismatched = run(wrong);
    const auto automatic = run(no_ack, true);
    INFO(unacked.size() << " stares unacknowledged, " << acked.size() << " acknowledged, "
                        << mismatched.size() << " with a wrong time, " << automatic.size()
                        << " with stare.auto_ack");
    REQUIRE(unacked.size() >= 3);
    for (const auto* stares : {&acked, &automatic}) {
        REQUIRE(stares->size() > unacked.size());  // each stare ends as it begins
        for (std::size_t i = 1; i < stares->size(); ++i) {
            CHECK((*stares)[i]["prev_stare_terminated_by_time"] == false);
            CHECK((*stares)[i]["prev_stare_time_s"].get<double>() < 0.3);
        }
    }
    CHECK(mismatched.size() == unacked.size());  // a wrong echo ends nothing
    for (std::size_t i = 1; i < unacked.size(); ++i)
        CHECK(unacked[i]["prev_stare_terminated_by_time"] == true);

    // Before any stare the time must be given.
    MavlinkDeviceProtocol fresh(MavlinkDeviceOptions{});
    command::Plan plan;
    const auto error = fresh.plan("stare_ack", json::object(), {1.0, 1.79e9}, plan);
    REQUIRE(error);
    CHECK(error->code == command::ErrorCode::unavailable);
    CHECK_FALSE(fresh.plan("stare_ack", {{"system_time_ms", 5}}, {1.0, 1.79e9}, plan));
}
