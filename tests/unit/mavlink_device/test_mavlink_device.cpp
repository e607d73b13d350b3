// MAVLink gimbal devices (contract section 19): the session's STATE from the device's
// messages, the commands' GIMBAL_DEVICE_SET_ATTITUDE against common.xml's definition, the
// vehicle feed's AUTOPILOT_STATE_FOR_GIMBAL_DEVICE, the simulated device, and the stare
// target (line of sight on a geopoint while the aircraft circles it), bytes in and out.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "device_fixtures.hpp"
#include "geo/wgs84.hpp"
#include "gimbal_protocol/status.hpp"
#include "mavlink/framer.hpp"
#include "protocols/mavlink_device/mavlink_device_protocol.hpp"
#include "protocols/mavlink_device/mavlink_device_sim.hpp"
#include "protocols/orion/orion_capabilities.hpp"
#include "protocols/registry.hpp"

using namespace gimbal;
using nlohmann::json;
using protocols::MavlinkDeviceOptions;
using protocols::MavlinkDeviceProtocol;
using vehicle_fixtures::from;
using namespace device_fixtures;

TEST_CASE("position: the quaternion of common.xml's GIMBAL_DEVICE_SET_ATTITUDE") {
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    // common.xml: q is w, x, y, z (Hamilton), the rotation from the vehicle frame (yaw from the
    // nose, pitch and roll from the horizon) to the camera's; roll 0, pitch = tilt, yaw = pan
    // give q = qz(pan) * qy(tilt).
    for (const auto& [pan, tilt] : {std::pair{30.0, -45.0}, {-120.0, 10.0}, {0.0, -90.0}}) {
        INFO("pan " << pan << " tilt " << tilt);
        const auto m = planned_attitude(p, "position", {{"pan", pan}, {"tilt", tilt}});
        const double cy = std::cos(pan * deg / 2), sy = std::sin(pan * deg / 2);
        const double cp = std::cos(tilt * deg / 2), sp = std::sin(tilt * deg / 2);
        CHECK(m.q[0] == Approx(cy * cp).margin(1e-6));
        CHECK(m.q[1] == Approx(-sy * sp).margin(1e-6));
        CHECK(m.q[2] == Approx(cy * sp).margin(1e-6));
        CHECK(m.q[3] == Approx(sy * cp).margin(1e-6));
        // Yaw from the vehicle's nose, roll and pitch held level; no rates.
        CHECK(m.flags == (4 | 8 | 32));
        CHECK(std::isnan(m.angular_velocity_y));
        CHECK(m.target_component == 154);
    }
}

TEST_CASE("center: yaw 0 and pitch 0 from the vehicle's nose, held") {
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    (void)planned_attitude(p, "position", {{"pan", 40}, {"tilt", -30}});
    const auto m = planned_attitude(p, "center", json::object());
    CHECK(m.q[0] == Approx(1).margin(1e-6));  // the identity: forward and level
    CHECK(m.q[1] == Approx(0).margin(1e-6));
    CHECK(m.q[2] == Approx(0).margin(1e-6));
    CHECK(m.q[3] == Approx(0).margin(1e-6));
    CHECK(m.flags == (4 | 8 | 32));
}

TEST_CASE("rate: angular velocities with a NaN quaternion; an impulse stops") {
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    const auto m = planned_attitude(p, "rate", {{"pan", 20}, {"tilt", -10}, {"impulse_time_s", 1}});
    CHECK(std::isnan(m.q[0]));
    CHECK(m.angular_velocity_z == Approx(20 * deg));
    CHECK(m.angular_velocity_y == Approx(-10 * deg));
    // After the impulse the steering tick asks for zero rates.
    vehicle::VehicleState v(vehicle_fixtures::options());
    std::vector<session::Bytes> out;
    p.steer(v, 0, 2.5, out);
    mavlink::GimbalDeviceSetAttitude last;
    for (const auto& msg : decode(out))
        if (const auto* s = std::get_if<mavlink::GimbalDeviceSetAttitude>(&msg.payload)) last = *s;
    CHECK(last.angular_velocity_z == 0.0f);
}

TEST_CASE("geopoint and path need the vehicle's fix; refused commands change nothing") {
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    command::Plan plan;
    const auto e = p.plan("geopoint", {{"lat", 45.7}, {"lon", -121.5}, {"alt", 0}}, {1, 0}, plan);
    REQUIRE(e);
    CHECK(e->code == command::ErrorCode::unavailable);
    CHECK(plan.packets.empty());
    const auto bad = p.plan("position", {{"pan", 300}, {"tilt", 0}}, {1, 0}, plan);
    REQUIRE(bad);
    CHECK(bad->code == command::ErrorCode::out_of_range);
    // Nothing held: the steering tick sends no set-attitude.
    vehicle::VehicleState v(vehicle_fixtures::options());
    std::vector<session::Bytes> out;
    p.steer(v, 0, 1.0, out);
    for (const auto& msg : decode(out))
        CHECK_FALSE(std::holds_alternative<mavlink::GimbalDeviceSetAttitude>(msg.payload));
}

TEST_CASE("without a vehicle feed the device's reports pace the heartbeat and the request") {
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    std::vector<state::Event> events;
    const auto replies_at = [&](double t) {
        std::vector<session::Bytes> replies;
        p.receive(device_frame(status(0, 0, 0, 32)), t, events, replies);
        return decode(replies);
    };
    auto r = replies_at(1.0);
    REQUIRE(r.size() == 2);
    CHECK(std::holds_alternative<mavlink::Heartbeat>(r[0].payload));
    const auto& request = std::get<mavlink::CommandLong>(r[1].payload);
    CHECK(request.command == 512);
    CHECK(request.param[0] == 283.0f);
    CHECK(request.target_system == 7);  // the device as heard
    CHECK(replies_at(1.5).empty());
    r = replies_at(2.1);
    REQUIRE(r.size() == 1);
    CHECK(std::holds_alternative<mavlink::Heartbeat>(r[0].payload));
    CHECK(replies_at(3.1).size() == 2);  // a second heartbeat, the request again after 2 s
}

TEST_CASE("STATE device: information and attitude, yaw frames per common.xml") {
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    auto s0 = p.snapshot(0);
    CHECK(s0["device"]["attitude"].is_null());
    CHECK(s0["telemetry"].is_null());
    CHECK(p.stale(0));

    mavlink::GimbalDeviceInformation info;
    const char vendor[] = "Gremsy";
    std::copy(vendor, vendor + 6, info.vendor_name.begin());
    const char model[] = "T7";
    std::copy(model, model + 2, info.model_name.begin());
    info.firmware_version = 7 | (4 << 8) | (2 << 16);
    info.cap_flags = 32 | 256 | 4096;
    info.pitch_min = static_cast<float>(-2.0);
    info.pitch_max = static_cast<float>(0.5);
    receive(p, device_frame(info), 1.0);
    // 32: YAW_IN_VEHICLE_FRAME; 64: YAW_IN_EARTH_FRAME; 16 alone: YAW_LOCK (the older rule).
    for (const auto& [flags, frame] : {std::pair{std::uint16_t{32}, "vehicle"},
                                       {std::uint16_t{64}, "earth"},
                                       {std::uint16_t{16}, "earth"},
                                       {std::uint16_t{16 | 32}, "vehicle"},
                                       {std::uint16_t{0}, "vehicle"}}) {
        auto st = status(0, -30, 20, flags);
        st.failure_flags = 2 | 512;
        receive(p, device_frame(st), 1.5);
        const auto d = p.snapshot(1.7)["device"];
        INFO(d.dump());
        CHECK(d["attitude"]["frame"] == frame);
        CHECK(d["attitude"]["pitch"].get<double>() == Approx(-30).margin(1e-4));
        CHECK(d["attitude"]["yaw"].get<double>() == Approx(20).margin(1e-4));
        CHECK(d["angular_velocity"][1].get<double>() == Approx(10).margin(1e-4));
        CHECK(d["angular_velocity"][2].get<double>() == Approx(-5).margin(1e-4));
        CHECK(d["failure_flags"] == json{"at_pitch_limit", "no_manager"});
        CHECK(d["age_s"].get<double>() == Approx(0.2));
        CHECK(d["vendor"] == "Gremsy");
        CHECK(d["model"] == "T7");
        CHECK(d["firmware"] == "7.4.2");  // Dev 0: a release
        CHECK(d["cap_flags"] ==
              json{"has_pitch_axis", "has_yaw_axis", "supports_yaw_in_earth_frame"});
        CHECK(d["limits"]["pitch_min"].get<double>() == Approx(-2.0 / deg).margin(1e-3));
        CHECK(d["limits"]["yaw_min"].is_null());
    }
    info.firmware_version |= 9u << 24;  // a development build
    receive(p, device_frame(info), 1.8);
    CHECK(p.snapshot(1.8)["device"]["firmware"] == "7.4.2.9");
    CHECK(p.telemetry_count() == 5);
    CHECK_FALSE(p.stale(2.0));
    CHECK(p.stale(2.6));  // stale_after_s 1.0
    std::vector<state::Event> events;
    p.tick(2.6, events);
    REQUIRE(events.size() == 1);
    CHECK(events[0].kind == "lost");
}

TEST_CASE("STATE telemetry: Orion's derived keys from the vehicle and the device") {
    MavlinkDeviceOptions o;
    o.hfov_deg = 40;
    o.vfov_deg = 30;
    o.geoid_undulation_m = -20;
    o.ground_alt_m = -20;  // flat ground at MSL 0
    MavlinkDeviceProtocol p(o);
    vehicle::VehicleState v(vehicle_fixtures::options());
    Aircraft a;  // 500 m MSL, heading east
    report(v, a, 1.0);
    std::vector<session::Bytes> out;
    p.steer(v, 1.0, 1.0, out);
    // Pan 90 (right of an east heading: south), tilt -45: the ground 500 m south.
    receive(p, device_frame(status(0, -45, 90, 32)), 1.0);
    const auto state = p.snapshot(1.0);
    const auto& t = state["telemetry"];
    INFO(t.dump());
    CHECK(t["lat"].get<double>() == Approx(45.7));
    CHECK(t["alt_msl"].get<double>() == Approx(500));
    CHECK(t["alt"].get<double>() == Approx(480));
    CHECK(t["pan"].get<double>() == Approx(90).margin(1e-3));
    CHECK(t["tilt"].get<double>() == Approx(-45).margin(1e-3));
    CHECK(t["hfov"] == 40);
    REQUIRE(t["target"].is_object());
    const auto look = geo::look_angles(
        {45.7, -121.5, 480}, {t["target"]["lat"].get<double>(), t["target"]["lon"].get<double>(),
                              t["target"]["alt"].get<double>()});
    CHECK(std::abs(look.azimuth_deg) == Approx(180).margin(0.05));
    CHECK(look.elevation_deg == Approx(-45).margin(0.05));
    CHECK(t["target"]["alt"].get<double>() == Approx(-20).margin(0.01));
    CHECK(t["footprint"].is_array());
    CHECK(t["ground"].is_object());
    // The capabilities read the same state.
    const auto& caps = p.capabilities();
    const auto los = caps.line_of_sight();
    REQUIRE(los);
    const auto e = geo::quat_to_euler(*los);
    CHECK(std::abs(e.yaw_deg) == Approx(180).margin(1e-3));
    CHECK(caps.view().lat_deg.value() == Approx(45.7));
    CHECK(caps.identity().vendor == "MAVLink");
    session::AnglesTarget target;
    target.yaw_deg = 10.0;
    const auto r = caps.point_angles(target);
    REQUIRE(r);
    CHECK(r.value() == json{{"cmd", "position"}, {"pan", 10.0}, {"tilt", -45.0}});
}

TEST_CASE("the vehicle feed: AUTOPILOT_STATE_FOR_GIMBAL_DEVICE at every tick, one sender") {
    const auto* e = protocols::find("mavlink");
    REQUIRE(e != nullptr);
    // The feeder only names the feed: the session sends, with its one sequence counter.
    auto feeder = e->make_feeder({{"name", "g"}, {"protocol", "mavlink"}});
    CHECK(feeder->kind() == "autopilot_state");
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    vehicle::VehicleState v(vehicle_fixtures::options());
    std::vector<session::Bytes> out;
    feeder->tick(v, {1.0, 0, 0}, out);
    CHECK(out.empty());
    const auto autopilot_states = [](const std::vector<mavlink::Message>& messages) {
        std::vector<mavlink::AutopilotStateForGimbalDevice> found;
        for (const auto& m : messages)
            if (const auto* a = std::get_if<mavlink::AutopilotStateForGimbalDevice>(&m.payload))
                found.push_back(*a);
        return found;
    };
    CHECK(p.steer(v, 1.0, 1.0, out) == 0);
    CHECK(autopilot_states(decode(out)).empty());  // nothing known of the vehicle
    Aircraft a;
    a.roll = 10;
    a.yaw = -60;
    a.vn = 12;
    report(v, a, 1.0);
    // Each tick's first frame is the feed's: STATE vehicle.feed.sent counts it.
    for (int tick = 0; tick < 4; ++tick) {
        std::vector<session::Bytes> one;
        CHECK(p.steer(v, 1.0 + tick * 0.05, 1.0 + tick * 0.05, one) == 1);
        REQUIRE_FALSE(one.empty());
        CHECK(autopilot_states(decode({one.front()})).size() == 1);
        out.insert(out.end(), one.begin(), one.end());
    }
    const auto messages = decode(out);
    const auto states = autopilot_states(messages);
    REQUIRE(states.size() == 4);
    const auto& m = states[0];
    const auto att = geo::quat_to_euler(geo::Quat{m.q[0], m.q[1], m.q[2], m.q[3]});
    CHECK(att.roll_deg == Approx(10).margin(1e-3));
    CHECK(att.yaw_deg == Approx(-60).margin(1e-3));
    CHECK(m.vx == Approx(12));
    CHECK(m.target_component == 154);
    CHECK((m.estimator_status & 1) != 0);
    // Heartbeat, information request and AUTOPILOT_STATEs: one sequence, no gaps.
    REQUIRE(messages.size() > states.size());
    for (std::size_t i = 1; i < messages.size(); ++i)
        CHECK(messages[i].seq == static_cast<std::uint8_t>(messages[i - 1].seq + 1));

    // The fix goes stale (vehicle.timeout_s 1 s): once without it, then nothing.
    out.clear();
    for (int tick = 0; tick < 3; ++tick) p.steer(v, 2.5 + tick * 0.05, 2.5 + tick * 0.05, out);
    const auto lost = autopilot_states(decode(out));
    REQUIRE(lost.size() == 1);
    CHECK(lost[0].estimator_status == 0);
    CHECK(std::isnan(lost[0].q[0]));
}

TEST_CASE("limits no gimbal has are unknown, and not relayed to ground stations") {
    // Contract section 14 (v4): a device reported +-5.7e39 degrees and inverted pitch limits,
    // and GIMBAL_MANAGER_INFORMATION passed them on.
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    mavlink::GimbalDeviceInformation info;
    info.roll_min = -1e38f;  // rad: -5.7e39 degrees
    info.roll_max = 1e38f;
    info.pitch_min = 0.5f;  // inverted
    info.pitch_max = -0.5f;
    info.yaw_min = static_cast<float>(-400 * deg);  // beyond a whole turn either way
    info.yaw_max = static_cast<float>(100 * deg);
    receive(p, device_frame(info), 1.0);
    receive(p, device_frame(status(0, -30, 20, 32)), 1.0);
    const auto state = p.snapshot(1.0);
    const auto& limits = state["device"]["limits"];
    INFO(limits.dump());
    for (const char* key : {"roll_min", "roll_max", "pitch_min", "pitch_max", "yaw_min"})
        CHECK(limits[key].is_null());
    CHECK(limits["yaw_max"].get<double>() == Approx(100).margin(1e-3));  // sane on its own
    const auto l = p.capabilities().limits();
    CHECK_FALSE(l.tilt_min_deg);
    CHECK_FALSE(l.pan_min_deg);
    // What the gimbal manager relays: the defaults for unknown limits, never the absurd ones.
    const gimbal_protocol::ExposedGimbal g{"g", "mavlink", 1, 154};
    const session::GimbalView view{&p.capabilities(), p.telemetry(), true, false, {}, {}};
    const auto m = gimbal_protocol::manager_information(g, view, 0);
    CHECK(m.pitch_min == Approx(-std::numbers::pi / 2));
    CHECK(m.pitch_max == Approx(std::numbers::pi / 2));
    CHECK(m.yaw_min == Approx(-std::numbers::pi));
    CHECK(m.yaw_max == Approx(std::numbers::pi));
    const auto d = gimbal_protocol::device_information(g, view, 0);
    CHECK(std::isnan(d.pitch_min));
    CHECK(std::isnan(d.pitch_max));

    // Inverted limits another gimbal reports (an Orion's LIMITS: pitch 30..-90, yaw beyond a
    // whole turn) are dropped by the manager as well.
    state::OrionData orion;
    orion::Limits inverted;
    inverted.min_pos = {-30.0, 30 * deg};
    inverted.max_pos = {30.0, -90 * deg};
    orion.packets.limits = state::Received<orion::Limits>{inverted, nullptr, 0};
    const protocols::OrionCapabilities orion_caps(orion);
    const auto m2 =
        gimbal_protocol::manager_information(g, {&orion_caps, nullptr, true, false, {}, {}}, 0);
    CHECK(m2.pitch_min == Approx(-std::numbers::pi / 2));
    CHECK(m2.yaw_max == Approx(std::numbers::pi));
}

TEST_CASE("the simulated device: information on request, slew rate and angle limits") {
    protocols::MavlinkDeviceSimOptions o;
    o.slew_rate_dps = 50;
    o.pitch_min_deg = -60;
    protocols::MavlinkDeviceSim sim(o);
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    for (const auto& b : p.on_connect()) sim.receive(b, 0.0);
    std::vector<std::uint8_t> out;
    sim.advance(0.1, out);
    receive(p, out, 0.1);
    const auto d = p.snapshot(0.1)["device"];
    CHECK(d["vendor"] == "gimbald");
    CHECK(d["firmware"] == "2.4.1");
    CHECK(d["limits"]["pitch_min"].get<double>() == Approx(-60).margin(1e-3));
    CHECK(p.state().earth_frame_supported());

    // Pitch to -80 (below its limit): 50 deg/s gets it to -50 in a second, then -60.
    command::Plan plan;
    REQUIRE_FALSE(p.plan("position", {{"pan", 0}, {"tilt", -80}}, {0.1, 0}, plan));
    sim.receive(plan.packets.at(0).frame, 0.1);
    sim.advance(1.1, out);
    CHECK(sim.pitch_deg() == Approx(-50).margin(0.5));
    sim.advance(3.0, out);
    CHECK(sim.pitch_deg() == Approx(-60).margin(1e-6));
    // The manager's heartbeat (from the steering tick) clears NO_MANAGER.
    vehicle::VehicleState v(vehicle_fixtures::options());
    std::vector<session::Bytes> steering;
    p.steer(v, 3.0, 3.0, steering);
    for (const auto& b : steering) sim.receive(b, 3.0);
    out.clear();
    sim.advance(3.2, out);
    receive(p, out, 3.2);
    CHECK(p.snapshot(3.2)["device"]["failure_flags"] == json{"at_pitch_limit"});
}

TEST_CASE("stare: the line of sight stays on a geopoint while the aircraft circles it") {
    // The aircraft flies a 400 m circle at 30 m/s, 500 m above the point; gimbald steers at
    // 20 Hz and feeds the vehicle's state; the device reports at 20 Hz.
    const geo::Lla point{45.7, -121.5, 100};
    const double radius = 400, speed = 30, omega = speed / radius;
    const auto aircraft_at = [&](double t) {
        const double ang = omega * t;  // clockwise seen from above, from north of the point
        const geo::Vec3 offset{radius * std::cos(ang), radius * std::sin(ang), -500};
        const auto lla =
            geo::ecef_to_lla(geo::lla_to_ecef(point) + geo::ned_to_ecef(offset, point));
        Aircraft a;
        a.lat = lla.lat_deg;
        a.lon = lla.lon_deg;
        a.alt_msl = lla.alt_m;  // geoid 0
        a.vn = -speed * std::sin(ang);
        a.ve = speed * std::cos(ang);
        a.yaw = std::atan2(a.ve, a.vn) / deg;
        a.roll = 12;
        a.yaw_rate = omega / deg;
        return a;
    };
    MavlinkDeviceProtocol p(MavlinkDeviceOptions{});
    protocols::MavlinkDeviceSim sim(protocols::MavlinkDeviceSimOptions{});
    vehicle::VehicleState v(vehicle_fixtures::options());
    for (const auto& b : p.on_connect()) sim.receive(b, 0.0);
    std::vector<double> errors;
    bool commanded = false;
    for (int i = 1; i <= 3000; ++i) {  // 30 s
        const double t = i * 0.01;
        if (i % 5 == 0) {
            report(v, aircraft_at(t), t);
            std::vector<session::Bytes> out;
            p.steer(v, t, t, out);  // AUTOPILOT_STATE and the set-point
            if (!commanded) {
                command::Plan plan;
                REQUIRE_FALSE(
                    p.plan("geopoint",
                           {{"lat", point.lat_deg}, {"lon", point.lon_deg}, {"alt", point.alt_m}},
                           {t, 0}, plan));
                for (auto& packet : plan.packets) out.push_back(packet.frame);
                commanded = true;
            }
            for (const auto& b : out) sim.receive(b, t);
        }
        std::vector<std::uint8_t> bytes;
        sim.advance(t, bytes);
        receive(p, bytes, t);
        if (t > 2.0 && i % 10 == 0) {
            const auto state = p.snapshot(t);
            const auto los = p.capabilities().line_of_sight();
            REQUIRE(los);
            const auto& tel = state["telemetry"];
            const geo::Lla from{tel["lat"].get<double>(), tel["lon"].get<double>(),
                                tel["alt"].get<double>()};
            const geo::Vec3 want =
                geo::ecef_to_ned(geo::lla_to_ecef(point) - geo::lla_to_ecef(from), from);
            const geo::Vec3 have = geo::rotate(*los, geo::Vec3{1, 0, 0});
            const double c = geo::dot(want, have) / (geo::norm(want) * geo::norm(have));
            errors.push_back(std::acos(std::clamp(c, -1.0, 1.0)) / deg);
        }
    }
    REQUIRE(errors.size() > 200);
    std::sort(errors.begin(), errors.end());
    const double p95 = errors[errors.size() * 95 / 100];
    INFO("p95 " << p95 << " max " << errors.back());
    CHECK(p95 < 0.5);
}
