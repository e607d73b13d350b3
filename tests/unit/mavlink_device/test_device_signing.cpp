// MAVLink 2 message signing on the device link (gimbals[].mavlink.signing_key_file,
// gimbal-sim --signing-key): gimbald's session and the simulated device talk only when both
// sign with the same key; unsigned, forged and replayed frames are refused and counted, and
// change nothing. Bytes in and out, with the clocks passed in.
#include <catch2/catch.hpp>

#include "mavlink/framer.hpp"
#include "mavlink/signing.hpp"
#include "protocols/mavlink_device/mavlink_device_protocol.hpp"
#include "protocols/mavlink_device/mavlink_device_sim.hpp"

using namespace gimbal;
using nlohmann::json;
using protocols::MavlinkDeviceOptions;
using protocols::MavlinkDeviceProtocol;
using protocols::MavlinkDeviceSim;
using protocols::MavlinkDeviceSimOptions;

namespace {

constexpr double host_unix_s = 1'795'000'000.0;  // gimbald's clock, 2026

mavlink::SigningKey key_of(std::uint8_t fill) {
    mavlink::SigningKey k{};
    k.fill(fill);
    return k;
}

MavlinkDeviceOptions session_options(std::optional<mavlink::SigningKey> key) {
    MavlinkDeviceOptions o;
    o.signing_key = key;
    o.unix_clock = [] { return host_unix_s; };
    return o;
}

MavlinkDeviceSimOptions device_options(std::optional<mavlink::SigningKey> key) {
    MavlinkDeviceSimOptions o;
    o.signing_key = key;
    o.unix_time_s = 1'735'689'600.0;  // the device's idea of now: 2025, no clock of its own
    return o;
}

// The session and the device exchange bytes for `seconds`; returns every byte the device sent.
std::vector<std::uint8_t> run(MavlinkDeviceProtocol& session, MavlinkDeviceSim& device,
                              double from_s, double seconds) {
    std::vector<std::uint8_t> sent;
    if (from_s == 0)
        for (const auto& b : session.on_connect()) device.receive(b, 0.0);
    for (double t = from_s + 0.01; t <= from_s + seconds; t += 0.01) {
        std::vector<std::uint8_t> bytes;
        device.advance(t, bytes);
        sent.insert(sent.end(), bytes.begin(), bytes.end());
        std::vector<state::Event> events;
        std::vector<session::Bytes> replies;
        session.receive(bytes, t, events, replies);
        for (const auto& r : replies) device.receive(r, t);
    }
    return sent;
}

bool has_information(const MavlinkDeviceProtocol& session) {
    const json s = session.snapshot(0);
    return s["device"]["vendor"].is_string();
}

}  // namespace

TEST_CASE("signing: the same key on both sides - information, attitude and commands flow") {
    const auto key = key_of(0x5A);
    MavlinkDeviceProtocol session(session_options(key));
    MavlinkDeviceSim device(device_options(key));
    const auto sent = run(session, device, 0, 3.0);
    CHECK(has_information(session));
    CHECK(session.counters().decode_errors == 0);
    CHECK(session.counters().rx_packets > 20);

    // Every frame either side sends is signed with the key.
    mavlink::Framer check({.accept_signed = true, .signing_key = key});
    const auto frames = check.push(sent);
    REQUIRE_FALSE(frames.empty());
    for (const auto& m : frames) {
        REQUIRE(m.signature);
        CHECK(m.signature->verified);
    }
    for (const auto& f : session.on_connect()) {
        const auto m = check.push(f);
        REQUIRE(m.size() == 1);
        REQUIRE(m[0].signature);
        CHECK(m[0].signature->verified);
        // gimbald stamps its own clock.
        CHECK(m[0].signature->timestamp >= mavlink::signing_timestamp(host_unix_s));
    }

    // A command reaches the device: it slews to the set-point.
    command::Plan plan;
    REQUIRE_FALSE(
        session.plan("position", {{"pan", 40.0}, {"tilt", -20.0}}, {3.0, host_unix_s}, plan));
    for (const auto& p : plan.packets) device.receive(p.frame, 3.0);
    run(session, device, 3.0, 2.0);
    CHECK(device.yaw_deg() == Approx(40).margin(0.5));
    CHECK(device.pitch_deg() == Approx(-20).margin(0.5));
}

TEST_CASE("signing: a device with another key, or none, is not heard and hears nothing") {
    for (const auto& device_key :
         {std::optional(key_of(0x11)), std::optional<mavlink::SigningKey>()}) {
        INFO("device signs: " << device_key.has_value());
        MavlinkDeviceProtocol session(session_options(key_of(0x5A)));
        MavlinkDeviceSim device(device_options(device_key));
        run(session, device, 0, 3.0);
        CHECK_FALSE(has_information(session));
        CHECK(session.snapshot(0)["device"]["attitude"].is_null());
        CHECK(session.counters().decode_errors > 20);
        CHECK(session.counters().rx_packets == 0);
        // Nor does the device follow gimbald's commands.
        command::Plan plan;
        REQUIRE_FALSE(
            session.plan("position", {{"pan", 40.0}, {"tilt", -20.0}}, {3.0, host_unix_s}, plan));
        for (const auto& p : plan.packets) device.receive(p.frame, 3.0);
        run(session, device, 3.0, 2.0);
        CHECK(device.yaw_deg() == Approx(0).margin(1e-9));
    }
}

TEST_CASE("signing off: a signed device is not heard (the framer skips signed frames)") {
    MavlinkDeviceProtocol session(session_options(std::nullopt));
    MavlinkDeviceSim device(device_options(key_of(0x5A)));
    run(session, device, 0, 3.0);
    CHECK_FALSE(has_information(session));
    CHECK(session.counters().decode_errors > 20);
}

TEST_CASE("signing: a replayed frame is refused and changes nothing") {
    const auto key = key_of(0x5A);
    MavlinkDeviceProtocol session(session_options(key));
    MavlinkDeviceSim device(device_options(key));
    const auto early = run(session, device, 0, 1.0);
    run(session, device, 1.0, 2.0);
    const json before = session.snapshot(3.0)["device"]["attitude"];
    const auto refused = session.counters().decode_errors;
    std::vector<state::Event> events;
    std::vector<session::Bytes> replies;
    session.receive(early, 3.0, events, replies);  // a capture of the first second, again
    CHECK(session.counters().decode_errors > refused);
    CHECK(session.snapshot(3.0)["device"]["attitude"] == before);
}

TEST_CASE("signing keys: 32 bytes or 64 hex digits") {
    CHECK(mavlink::parse_signing_key(std::string(32, 'k')) == key_of('k'));
    const std::string hex(64, 'a');
    CHECK(mavlink::parse_signing_key(" " + hex + "\n") == key_of(0xAA));
    CHECK_FALSE(mavlink::parse_signing_key(hex.substr(2)));
    CHECK_FALSE(mavlink::parse_signing_key(std::string(63, 'a') + "g"));
    CHECK_FALSE(mavlink::parse_signing_key(""));
}
