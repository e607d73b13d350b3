// The simulated Orion's laser interlocks follow the AutopilotData the vehicle feed builds:
// ApFlyingLock (not flying), ApCommLock (CommGood 0) and AltitudeLock (AGL below the minimum).
#include <catch2/catch.hpp>

#include "protocols/orion/codec/packets.hpp"
#include "protocols/orion/orion_feed_packets.hpp"
#include "protocols/orion/sim/laser.hpp"
#include "sim_harness.hpp"

using namespace gimbal;
using sim_test::decoded;
using sim_test::Harness;

namespace {

mavlink::Message from_vehicle(mavlink::Payload payload) {
    mavlink::Message m;
    m.sysid = 1;
    m.compid = 1;
    m.msgid = mavlink::message_id(payload);
    m.payload = std::move(payload);
    return m;
}

mavlink::Heartbeat heartbeat(bool armed) {
    mavlink::Heartbeat hb;
    hb.type = 2;
    hb.autopilot = 3;
    hb.base_mode = armed ? mavlink::mav_mode_flag_safety_armed : 0;
    hb.system_status =
        static_cast<std::uint8_t>(armed ? mavlink::MavState::active : mavlink::MavState::standby);
    return hb;
}

mavlink::GlobalPositionInt at_agl(double agl_m) {
    mavlink::GlobalPositionInt p;
    p.relative_alt = static_cast<std::int32_t>(agl_m * 1000);
    return p;
}

// Feeds `ap` to the simulator, then asks laser 0 to fire; returns the answering states.
orion::LaserState fire_after(Harness& h, const orion::AutopilotData& ap, bool bypass = false) {
    h.send_packet(ap);
    orion::LaserCmd c;
    c.enable = c.arm = c.fire = true;
    c.safety_bypass = bypass;
    h.send_packet(c);
    const auto states = decoded<orion::LaserStates>(h.run(0.001, 0.001));
    REQUIRE(states.size() == 1);
    REQUIRE_FALSE(states[0].states.empty());
    return states[0].states[0];
}

}  // namespace

TEST_CASE("no AutopilotData yet: no autopilot interlock", "[sim][vehicle]") {
    Harness h;
    h.run(0.2);
    orion::LaserCmd c;
    c.enable = c.arm = c.fire = true;
    h.send_packet(c);
    const auto states = decoded<orion::LaserStates>(h.run(0.001, 0.001));
    REQUIRE(states.size() == 1);
    CHECK(states[0].states[0].active);
    CHECK_FALSE(states[0].states[0].ap_comm_lock);
}

TEST_CASE("the fed vehicle state sets and clears the simulator's interlocks", "[sim][vehicle]") {
    Harness h;
    h.run(0.2);
    vehicle::VehicleState v{vehicle::VehicleOptions{}};
    double t = 0;

    // Flying at 120 m with a fresh feed: fire allowed.
    v.apply(from_vehicle(heartbeat(true)), t);
    v.apply(from_vehicle(at_agl(120)), t);
    auto s = fire_after(h, vehicle::orion_autopilot_data(v, t));
    CHECK(s.active);
    CHECK_FALSE(s.altitude_lock);
    CHECK_FALSE(s.ap_comm_lock);
    CHECK_FALSE(s.ap_flying_lock);

    // Disarmed: ApFlyingLock, fire refused.
    v.apply(from_vehicle(heartbeat(false)), t += 0.1);
    s = fire_after(h, vehicle::orion_autopilot_data(v, t));
    CHECK(s.ap_flying_lock);
    CHECK_FALSE(s.active);

    // Low: AltitudeLock.
    v.apply(from_vehicle(heartbeat(true)), t += 0.1);
    v.apply(from_vehicle(at_agl(5)), t);
    s = fire_after(h, vehicle::orion_autopilot_data(v, t));
    CHECK(s.altitude_lock);
    CHECK_FALSE(s.ap_flying_lock);
    CHECK_FALSE(s.active);

    // A safety bypass fires anyway (the daemon only allows it when configured).
    s = fire_after(h, vehicle::orion_autopilot_data(v, t), true);
    CHECK(s.active);
    CHECK(s.bypass_enabled);

    // Feed lost: ApCommLock.
    v.apply(from_vehicle(at_agl(120)), t += 0.1);
    s = fire_after(h, vehicle::orion_autopilot_data(v, t + 5.0));
    CHECK(s.ap_comm_lock);
    CHECK_FALSE(s.active);
}

TEST_CASE("a laser firing without bypass stops when an interlock engages", "[sim][laser]") {
    sim::LaserBank bank({orion::LaserType::pointer}, "");
    sim::LaserRequest r;
    r.enable = r.arm = r.fire = true;
    CHECK(bank.command(r) == sim::LaserResult::applied);
    CHECK(bank.units()[0].active);
    sim::LaserInterlocks locks;
    locks.ap_comm = true;
    bank.set_interlocks(locks);
    CHECK_FALSE(bank.units()[0].active);
    CHECK(bank.units()[0].ap_comm_lock);
    CHECK(bank.command(r) == sim::LaserResult::fire_refused);
    bank.set_interlocks({});
    CHECK(bank.command(r) == sim::LaserResult::applied);
    CHECK_FALSE(bank.units()[0].ap_comm_lock);
}
