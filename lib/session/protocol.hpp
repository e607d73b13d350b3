// Everything protocol-specific about one gimbal, behind one interface, so the daemon has a
// single session, command and subscription path for every protocol:
// bytes in -> framer -> state (+ events); JSON command -> packets out. Pure: time is passed in.
// Each protocol's implementation is made by its registry entry (protocols/registry.hpp).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "command/result.hpp"
#include "session/capabilities.hpp"
#include "session/laser_guard.hpp"
#include "state/event.hpp"
#include "state/telemetry.hpp"
#include "state/writer.hpp"
#include "vehicle/vehicle_state.hpp"

namespace gimbal::session {

using Bytes = std::vector<std::uint8_t>;

// The two clocks a command may need: monotonic seconds for timers, UTC for wire time fields.
struct Now {
    double mono_s = 0;
    double unix_s = 0;
};

// Framer counters shown in the STATE `link` object.
struct FrameCounters {
    std::uint64_t rx_packets = 0;
    std::uint64_t bad_checksums = 0;
    std::uint64_t dropped_bytes = 0;
    std::uint64_t decode_errors = 0;
};

// What the session adds when a protocol's STATE keys are written.
struct StateContext {
    double now_s = 0;
    // The daemon's own record of each laser it commanded to fire (contract section 14:
    // STATE lasers[i].firing, as the metric gimbald_laser_firing); nullptr: not shown.
    const LaserGuard* lasers = nullptr;
};

class Protocol {
  public:
    virtual ~Protocol() = default;

    virtual std::string_view name() const = 0;  // the registry entry's name

    // Bytes from the gimbal at now_s. Appends the events they cause and the packets the
    // daemon answers with by itself (e.g. StareAck when stare.auto_ack is set).
    virtual void receive(std::span<const std::uint8_t> bytes, double now_s,
                         std::vector<state::Event>& events, std::vector<Bytes>& replies) = 0;
    virtual void tick(double now_s, std::vector<state::Event>& events) = 0;
    // At the same 100 ms ticks, whether or not the gimbal speaks or a vehicle feed runs: what
    // the protocol sends by itself (a camera that only answers when asked, and is asked again
    // while it is silent: SIYI). Sent only while the link is up. Default: nothing.
    virtual void poll(double /*now_s*/, std::vector<Bytes>& /*out*/) {}
    // The vehicle feed's 50 ms tick (protocols/vehicle_feeder.hpp) with the vehicle's state
    // (on its own clock, vehicle_now_s), for a protocol that aims its gimbal from it itself (a
    // MAVLink gimbal device): appends what to send. now_s is the session's clock. Returns how
    // many of the frames appended, the first ones, are the vehicle feed's (STATE
    // vehicle.feed.sent counts them).
    virtual std::size_t steer(const vehicle::VehicleState& /*vehicle*/, double /*vehicle_now_s*/,
                              double /*now_s*/, std::vector<Bytes>& /*out*/) {
        return 0;
    }
    // A new connection: forget partial frames; returns what to send first (requests).
    virtual std::vector<Bytes> on_connect() = 0;

    virtual bool stale(double now_s) const = 0;
    // Seconds since the latest position telemetry (Orion GeolocateTelemetry, a Viewpro OUTx
    // frame, a MAVLink device's attitude); nullopt before the first.
    virtual std::optional<double> telemetry_age_s(double now_s) const = 0;
    // Position telemetry frames received so far.
    virtual std::uint64_t telemetry_count() const = 0;
    // The protocol's keys of STATE (section 5), without protocol/link/stale, written from its
    // typed state at the edge (state/writer.hpp).
    virtual void write_state(state::JsonWriter& w, const StateContext& context) const = 0;
    // write_state() as a JSON object, without the session's parts (tests, tools).
    nlohmann::json snapshot(double now_s) const {
        nlohmann::json out = nlohmann::json::object();
        state::JsonWriter w(out);
        write_state(w, StateContext{now_s, nullptr});
        return out;
    }
    virtual FrameCounters counters() const = 0;

    virtual bool supports(std::string_view cmd) const = 0;
    // What the gimbal can do, bound to its typed state (session/capabilities.hpp).
    virtual const Capabilities& capabilities() const = 0;
    // STATE telemetry's shared part (state/telemetry.hpp); nullptr before the first report, or
    // for a protocol whose gimbal reports no position telemetry.
    virtual const state::Telemetry* telemetry() const { return nullptr; }
    // Plans a command; on error returns it and plans nothing.
    virtual std::optional<command::Error> plan(std::string_view cmd, const nlohmann::json& request,
                                               const Now& now, command::Plan& plan) = 0;
};

}  // namespace gimbal::session
