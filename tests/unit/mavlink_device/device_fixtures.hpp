// Builders shared by the MAVLink gimbal device tests: the aircraft's reports, the device's
// messages, and the set-attitude a command plans.
#pragma once

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string_view>
#include <vector>

#include "../vehicle/vehicle_fixtures.hpp"
#include "geo/attitude.hpp"
#include "mavlink/framer.hpp"
#include "protocols/mavlink_device/mavlink_device_protocol.hpp"

namespace device_fixtures {

using namespace gimbal;
using nlohmann::json;
using protocols::MavlinkDeviceProtocol;
using vehicle_fixtures::from;

inline constexpr double pi = std::numbers::pi;
inline constexpr double deg = pi / 180.0;

inline std::vector<mavlink::Message> decode(const std::vector<std::vector<std::uint8_t>>& frames) {
    mavlink::Framer framer;
    std::vector<mavlink::Message> out;
    for (const auto& f : frames)
        for (auto& m : framer.push(f)) out.push_back(std::move(m));
    return out;
}

inline std::vector<std::uint8_t> device_frame(const mavlink::Payload& p, std::uint8_t seq = 0) {
    return mavlink::encode_v2(p, 7, 154, seq);
}

// The aircraft's report at now_s: position (MSL), attitude and velocity.
struct Aircraft {
    double lat = 45.7, lon = -121.5, alt_msl = 500;
    double roll = 0, pitch = 0, yaw = 90;  // degrees
    double vn = 0, ve = 0, vd = 0;
    double yaw_rate = 0;  // deg/s
};

inline void report(vehicle::VehicleState& v, const Aircraft& a, double now_s) {
    mavlink::Heartbeat hb;
    hb.system_status = static_cast<std::uint8_t>(mavlink::MavState::active);
    v.apply(from(1, hb), now_s);
    mavlink::Attitude att;
    att.roll = static_cast<float>(a.roll * deg);
    att.pitch = static_cast<float>(a.pitch * deg);
    att.yaw = static_cast<float>(a.yaw * deg);
    att.yawspeed = static_cast<float>(a.yaw_rate * deg);
    v.apply(from(1, att), now_s);
    mavlink::GlobalPositionInt p;
    p.lat = static_cast<std::int32_t>(std::lround(a.lat * 1e7));
    p.lon = static_cast<std::int32_t>(std::lround(a.lon * 1e7));
    p.alt = static_cast<std::int32_t>(std::lround(a.alt_msl * 1e3));
    p.vx = static_cast<std::int16_t>(std::lround(a.vn * 100));
    p.vy = static_cast<std::int16_t>(std::lround(a.ve * 100));
    p.vz = static_cast<std::int16_t>(std::lround(a.vd * 100));
    v.apply(from(1, p), now_s);
}

inline mavlink::GimbalDeviceAttitudeStatus status(double roll, double pitch, double yaw,
                                                  std::uint16_t flags) {
    mavlink::GimbalDeviceAttitudeStatus s;
    const auto q = geo::euler_to_quat(geo::EulerDeg{roll, pitch, yaw});
    s.q = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
           static_cast<float>(q.z)};
    s.angular_velocity_x = 0;
    s.angular_velocity_y = static_cast<float>(10 * deg);
    s.angular_velocity_z = static_cast<float>(-5 * deg);
    s.flags = flags;
    return s;
}

inline void receive(MavlinkDeviceProtocol& p, const std::vector<std::uint8_t>& bytes,
                    double now_s) {
    std::vector<state::Event> events;
    std::vector<session::Bytes> replies;
    p.receive(bytes, now_s, events, replies);
}

inline mavlink::GimbalDeviceSetAttitude planned_attitude(MavlinkDeviceProtocol& p,
                                                         std::string_view cmd, const json& request,
                                                         double now_s = 1.0) {
    command::Plan plan;
    const auto error = p.plan(cmd, request, {now_s, 1.79e9}, plan);
    INFO((error ? error->message : "ok"));
    REQUIRE_FALSE(error);
    REQUIRE(plan.packets.size() == 1);
    CHECK(plan.packets[0].sent == json{{"id", 284}, {"len", 32}});
    const auto messages = decode({plan.packets[0].frame});
    REQUIRE(messages.size() == 1);
    return std::get<mavlink::GimbalDeviceSetAttitude>(messages[0].payload);
}

}  // namespace device_fixtures
