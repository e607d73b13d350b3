// A flight as the export formats see it: one point per telemetry packet (Orion
// GeolocateTelemetry, Viewpro OUT1..OUT4) with the aircraft position, the target and the
// camera footprint, decoded from the gimbal side of a recording. Pure.
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "record/gimbal_stream.hpp"

namespace gimbal::flight_export {

struct Position {
    double lat = 0;  // degrees
    double lon = 0;
    std::optional<double> alt;      // metres above the WGS84 ellipsoid
    std::optional<double> alt_msl;  // metres above mean sea level
};

struct TrackPoint {
    std::int64_t time_us = 0;  // receive time, microseconds since the Unix epoch
    // Property name -> JSON number, string or null (the CSV columns after "time"), in the
    // units of the interface contract: gimbal_time, system_time_ms, lat, lon, alt, pan, ...
    nlohmann::json values = nlohmann::json::object();
    std::optional<Position> aircraft;
    std::optional<Position> target;
    // Image corners on the ground (top-left, top-right, bottom-right, bottom-left), at the
    // target's altitude; Orion only (Viewpro frames carry no field of view).
    std::optional<std::array<Position, 4>> footprint;
};

struct Flight {
    std::string gimbal;
    std::string protocol;
    std::vector<TrackPoint> points;
    std::uint64_t frames = 0;         // valid frames decoded
    std::uint64_t decode_errors = 0;  // valid frames that did not decode
};

// Decodes the stream with the framer and codec of its protocol. False with `error` when the
// protocol is unknown.
bool build_flight(const record::GimbalStream& stream, Flight& out, std::string& error);

// The CSV columns after "time", in order.
const std::vector<std::string>& value_columns();

// A JSON number as text, whole numbers without ".0"; strings as they are; null as "".
std::string value_text(const nlohmann::json& value);

// "2026-11-25T12:00:00.123Z"
std::string iso_time(std::int64_t time_us);

// Points whose footprint is drawn: the first with one, then each first one at least
// every_s seconds (receive time) after the previous drawn one; every_s <= 0: all of them.
std::vector<const TrackPoint*> footprints_every(const Flight& flight, double every_s);

// The footprint as a closed ring wound counter-clockwise (RFC 7946 exterior ring): five
// positions, the last equal to the first.
std::array<Position, 5> counter_clockwise_ring(const std::array<Position, 4>& corners);

// Runs of consecutive points that have a target (a gap in ranging splits the track).
std::vector<std::vector<const TrackPoint*>> target_segments(const Flight& flight);

}  // namespace gimbal::flight_export
