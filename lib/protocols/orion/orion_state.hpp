// The live state of one Orion gimbal, built from the packets it sends (contract section 5),
// typed: the latest packet of each kind STATE shows, as the codec decoded it, and the shared
// telemetry derived from GeolocateTelemetry (state/telemetry.hpp). Its STATE keys are written
// at the edges by the state writer (state/writer.hpp), each packet as its codec writes it.
// Pure: every call takes `now_s` (monotonic seconds); the daemon passes its steady clock.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geo/surface.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "state/event.hpp"
#include "state/telemetry.hpp"
#include "state/writer.hpp"

namespace gimbal::state {

// STATE `telemetry` of an Orion: the latest GeolocateTelemetry, its fields as the codec writes
// them (contract digits: written once, when it arrives), its UTC, and the shared telemetry
// derived from it (state/telemetry.hpp), whose reported keys are the packet's own.
struct OrionTelemetry {
    orion::GeolocateTelemetry packet;
    nlohmann::json packet_json;
    std::optional<std::string> utc;  // nullopt: the gimbal has no GPS time yet
    Telemetry shared;
};

// The packet's telemetry; footprint and ground on `terrain` where it answers, else on the
// ellipsoid raised to the target's altitude.
OrionTelemetry orion_telemetry(const orion::GeolocateTelemetry& t, geo::Surface* terrain);

template <class V>
void fields(V& v, const OrionTelemetry& t) {
    v.members(t.packet_json);
    v.string("utc", t.utc);
    derived_fields(v, t.shared);
}

// A packet as it arrived: the packet, its JSON as the codec writes it with the contract's
// digits (written once, when it arrives: STATE shows it at every push) and when.
template <class P>
struct Received {
    P packet;
    nlohmann::json json;
    double received_s = 0;
};

// The latest packet of every kind an Orion's STATE shows, by its STATE key. Per-board packets
// (software, boards) are kept per board, the version packets per board too (STATE `versions`).
struct OrionPackets {
    std::optional<Received<orion::InsQuality>> ins;
    std::optional<Received<orion::GpsData>> gps;
    std::optional<Received<orion::LaserStates>> lasers;
    std::optional<Received<orion::Diagnostics>> diagnostics;
    std::optional<Received<orion::Performance>> performance;
    std::map<std::string, Received<orion::SoftwareDiagnostics>> software;
    std::optional<Received<orion::NetworkDiagnostics>> network_diagnostics;
    std::optional<Received<orion::Vibration>> vibration;
    std::optional<Received<orion::RetractStatus>> retract;
    std::optional<Received<orion::StareStart>> stare;
    std::optional<Received<orion::Cameras>> cameras;
    std::optional<Received<orion::Limits>> limits;
    std::optional<Received<orion::NetworkSettings>> network_settings;
    std::optional<Received<orion::NetworkVideo>> network_video;
    std::optional<Received<orion::UartConfig>> uart_config;
    std::optional<Received<orion::InsOptions>> ins_options;
    std::optional<Received<orion::ResetSource>> reset_source;
    std::map<std::string, Received<orion::BoardInfo>> boards;
    std::optional<Received<orion::ClevisVersion>> clevis_version;
    std::optional<Received<orion::CrownVersion>> crown_version;
    std::optional<Received<orion::PayloadVersion>> payload_version;
    std::optional<Received<orion::TrackerVersion>> tracker_version;
    std::optional<Received<orion::RetractVersion>> retract_version;
    std::optional<Received<orion::LensCtlVersion>> lensctl_version;
};

// What an Orion has reported, typed: what its capabilities read (orion_capabilities.hpp).
struct OrionData {
    OrionPackets packets;
    std::optional<OrionTelemetry> telemetry;
};

// A number of a packet as STATE shows it (the codec's digits), found by the member's address;
// nullopt when it is not finite. `index` picks an element of an array field.
template <class P, class T>
std::optional<double> shown(const P& packet, const T& member) {
    const nlohmann::json v = orion::field_json(packet, member, orion::Digits::shortest);
    return v.is_number() ? std::optional(v.get<double>()) : std::nullopt;
}
template <class P, class T>
std::optional<double> shown(const P& packet, const T& member, std::size_t index) {
    const nlohmann::json v = orion::field_json(packet, member, orion::Digits::shortest);
    if (!v.is_array() || index >= v.size() || !v[index].is_number()) return std::nullopt;
    return v[index].get<double>();
}

class OrionState {
  public:
    // `terrain` (nullptr: none) is where telemetry's footprint and ground meet the ground
    // (state/telemetry.hpp); it must outlive the state.
    explicit OrionState(double stale_after_s = 1.0, geo::Surface* terrain = nullptr)
        : stale_after_s_(stale_after_s), terrain_(terrain) {}

    // Applies one checksum-valid frame received at now_s and appends the events it causes
    // (mode, stare_start, debug). Returns false when the packet did not decode (too short):
    // it changes nothing and `last_decode_error()` says why.
    bool apply(const orion::Frame& frame, double now_s, std::vector<Event>& events);

    // Time-driven changes: appends a `lost` event when telemetry goes stale.
    void tick(double now_s, std::vector<Event>& events);

    bool stale(double now_s) const;
    // Seconds since the latest GeolocateTelemetry; nullopt before the first.
    std::optional<double> telemetry_age_s(double now_s) const {
        if (!data_.telemetry) return std::nullopt;
        return std::max(0.0, now_s - telemetry_s_);
    }
    // GeolocateTelemetry packets applied so far (streams that follow new telemetry).
    std::uint64_t telemetry_count() const { return telemetry_count_; }

    // The Orion keys of STATE: one per packet kind, null until first received, each with
    // age_s; lasers[i].firing from `firing` when given (the daemon's own record).
    void write(JsonWriter& w, double now_s,
               const std::function<bool(std::uint8_t)>& firing = nullptr) const;
    // write() as a JSON object, without `firing`.
    nlohmann::json snapshot(double now_s) const;

    const std::optional<OrionTelemetry>& telemetry() const { return data_.telemetry; }
    const OrionPackets& packets() const { return data_.packets; }
    const OrionData& data() const { return data_; }
    std::optional<std::uint32_t> last_stare_time_ms() const { return last_stare_time_ms_; }
    std::uint64_t decode_errors() const { return decode_errors_; }
    const std::string& last_decode_error() const { return last_decode_error_; }

  private:
    template <class P>
    void store(const P& packet, nlohmann::json json, double now_s);
    void on_telemetry(const orion::GeolocateTelemetry& t, double now_s, std::vector<Event>& events);

    double stale_after_s_;
    geo::Surface* terrain_;
    OrionData data_;
    double telemetry_s_ = 0;
    std::uint64_t telemetry_count_ = 0;
    bool lost_reported_ = false;
    std::optional<std::uint32_t> last_stare_time_ms_;
    std::uint64_t decode_errors_ = 0;
    std::string last_decode_error_;
};

// Derived telemetry values (contract section 5), exposed for tests and the simulator.
// UTC from GPS week and time of week minus leap seconds, ISO-8601 with milliseconds.
std::string gps_to_utc_iso(std::uint16_t week, std::uint32_t itow_ms, std::uint8_t leap_seconds);
// STATE `telemetry` of one packet, without age_s (orion_telemetry(), written).
nlohmann::json telemetry_json(const orion::GeolocateTelemetry& t, geo::Surface* terrain = nullptr);

}  // namespace gimbal::state
