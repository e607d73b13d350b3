// libFuzzer target for the MAVLink gimbal device protocol (lib/protocols/mavlink_device): the
// input, in chunks it chooses itself, is what the device sends (to gimbald's session) and
// what the manager sends (to the simulated device); between chunks the session steers from a
// vehicle, plans a command and renders STATE, and the capabilities read that state; with or
// without MAVLink signing on the link. Any crash, sanitizer report or broken invariant aborts.
#include <cstdio>
#include <cstdlib>
#include <span>

#include "mavlink/mavlink.hpp"
#include "protocols/mavlink_device/mavlink_device_protocol.hpp"
#include "protocols/mavlink_device/mavlink_device_sim.hpp"

namespace p = gimbal::protocols;
namespace mav = gimbal::mavlink;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_mavlink_device: %s\n", what);
    std::abort();
}

mav::Message from_autopilot(mav::Payload payload) {
    mav::Message m;
    m.sysid = 1;
    m.compid = 1;
    m.msgid = mav::message_id(payload);
    m.payload = std::move(payload);
    return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> input(data, size);
    // An odd first byte: both ends sign (the signature and replay checks see the input).
    p::MavlinkDeviceOptions session_options;
    p::MavlinkDeviceSimOptions device_options;
    if (size > 0 && (data[0] & 1) != 0) {
        mav::SigningKey key{};
        key.fill(0x42);
        session_options.signing_key = device_options.signing_key = key;
        session_options.unix_clock = [] { return 1.8e9; };
        device_options.unix_time_s = 1.7e9;
    }
    p::MavlinkDeviceProtocol session(session_options);
    p::MavlinkDeviceSim device(device_options);
    gimbal::vehicle::VehicleState vehicle(gimbal::vehicle::VehicleOptions{});
    mav::Heartbeat hb;
    vehicle.apply(from_autopilot(hb), 0.0);
    mav::GlobalPositionInt pos;
    pos.lat = 457000000;
    pos.lon = -1215000000;
    pos.alt = 500000;
    std::vector<gimbal::state::Event> events;
    std::vector<gimbal::session::Bytes> out;
    double t = 0;
    std::size_t i = 0;
    while (i < input.size()) {
        const std::uint8_t control = input[i++];
        const std::size_t n = std::min<std::size_t>(1 + control % 97, input.size() - i);
        const auto chunk = input.subspan(i, n);
        i += n;
        t += 0.01 * (control % 7);
        if (control & 0x80) {
            device.receive(chunk, t);
        } else {
            session.receive(chunk, t, events, out);
        }
        // The aircraft somewhere (from the input), then a steering tick and a command.
        mav::Attitude att;
        att.yaw = static_cast<float>(control) / 40.0f;
        att.roll = static_cast<float>(n) / 100.0f;
        vehicle.apply(from_autopilot(att), t);
        vehicle.apply(from_autopilot(pos), t);
        out.clear();
        session.steer(vehicle, t, t, out);
        for (const auto& bytes : out) device.receive(bytes, t);
        gimbal::command::Plan plan;
        const double a = static_cast<double>(control) - 128.0;
        switch (control % 4) {
            case 0:
                (void)session.plan("position", {{"pan", a}, {"tilt", a / 2}}, {t, 0}, plan);
                break;
            case 1:
                (void)session.plan("rate", {{"pan", a}, {"tilt", -a}}, {t, 0}, plan);
                break;
            case 2:
                (void)session.plan("geopoint", {{"lat", 45.7}, {"lon", -121.5}, {"alt", a}}, {t, 0},
                                   plan);
                break;
            default:
                (void)session.plan("path",
                                   {{"points", {{{"lat", 45.7}, {"lon", -121.5}, {"alt", 0}}}},
                                    {"along_step_deg", control % 30}},
                                   {t, 0}, plan);
                break;
        }
        for (const auto& packet : plan.packets) device.receive(packet.frame, t);
        std::vector<std::uint8_t> produced;
        device.advance(t, produced);
        session.receive(produced, t, events, out);
        session.tick(t, events);
        const auto state = session.snapshot(t);
        if (!state.contains("device") || !state.contains("telemetry"))
            fail("STATE without device or telemetry");
        (void)state.dump();
        const auto& caps = session.capabilities();
        (void)caps.line_of_sight();
        (void)caps.view();
        (void)caps.image();
        (void)caps.identity();
        const auto c = session.counters();
        if (c.rx_packets > size * 8 + produced.size() * 64) fail("more frames than bytes");
    }
    return 0;
}
