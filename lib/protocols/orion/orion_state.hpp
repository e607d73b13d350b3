// The live state of one Orion gimbal, built from the packets it sends (contract section 5).
// Pure: every call takes `now_s` (monotonic seconds); the daemon passes its steady clock.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geo/surface.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "state/event.hpp"

namespace gimbal::state {

class OrionState {
  public:
    // `terrain` (nullptr: none) is where telemetry's footprint and ground meet the ground
    // (state/ground_json.hpp); it must outlive the state.
    explicit OrionState(double stale_after_s = 1.0, geo::Surface* terrain = nullptr)
        : stale_after_s_(stale_after_s), terrain_(terrain) {}

    // Applies one checksum-valid frame received at now_s and appends the events it causes
    // (mode, stare_start, debug). Returns false when the packet did not decode (too short):
    // it changes nothing and `last_decode_error()` says why.
    bool apply(const orion::Frame& frame, double now_s, std::vector<Event>& events);

    // Time-driven changes: appends a `lost` event when telemetry goes stale.
    void tick(double now_s, std::vector<Event>& events);

    bool stale(double now_s) const;
    // GeolocateTelemetry packets applied so far (streams that follow new telemetry).
    std::uint64_t telemetry_count() const { return telemetry_count_; }
    // The Orion keys of STATE: one per packet kind, null until first received, each with age_s.
    nlohmann::json snapshot(double now_s) const;

    const std::optional<orion::GeolocateTelemetry>& telemetry() const { return telemetry_; }
    std::optional<std::uint32_t> last_stare_time_ms() const { return last_stare_time_ms_; }
    std::uint64_t decode_errors() const { return decode_errors_; }
    const std::string& last_decode_error() const { return last_decode_error_; }

  private:
    struct Entry {
        nlohmann::json value;
        double received_s = 0;
    };
    void store(const std::string& key, nlohmann::json value, double now_s);
    void store_keyed(const std::string& key, const std::string& sub, nlohmann::json value,
                     double now_s);
    void on_telemetry(const orion::GeolocateTelemetry& t, double now_s, std::vector<Event>& events);

    double stale_after_s_;
    geo::Surface* terrain_;
    std::map<std::string, Entry> entries_;
    std::map<std::string, std::map<std::string, Entry>> keyed_;  // versions, software, boards
    std::optional<orion::GeolocateTelemetry> telemetry_;
    std::optional<double> telemetry_s_;
    std::uint64_t telemetry_count_ = 0;
    bool lost_reported_ = false;
    std::optional<std::uint32_t> last_stare_time_ms_;
    std::uint64_t decode_errors_ = 0;
    std::string last_decode_error_;
};

// Derived telemetry values (contract section 5), exposed for tests and the simulator.
// UTC from GPS week and time of week minus leap seconds, ISO-8601 with milliseconds.
std::string gps_to_utc_iso(std::uint16_t week, std::uint32_t itow_ms, std::uint8_t leap_seconds);
// STATE `telemetry`; footprint and ground on `terrain` where it answers, else on the
// ellipsoid raised to the target's altitude.
nlohmann::json telemetry_json(const orion::GeolocateTelemetry& t, geo::Surface* terrain = nullptr);

}  // namespace gimbal::state
