// A flight as the export formats see it: one point per telemetry frame with the aircraft
// position, the target and the camera footprint, decoded from the gimbal side of a recording
// by its protocol's export hook (the registry's TrackDecoder). Pure.
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "protocols/track.hpp"
#include "record/gimbal_stream.hpp"

namespace gimbal::flight_export {

// The registry's track points (protocols/track.hpp): each protocol's export hook makes them.
using Position = protocols::TrackPosition;
using TrackPoint = protocols::TrackPoint;

struct Flight {
    std::string gimbal;
    std::string protocol;
    std::vector<TrackPoint> points;
    std::uint64_t frames = 0;         // valid frames decoded
    std::uint64_t decode_errors = 0;  // valid frames that did not decode
};

// Decodes the stream with its protocol's track decoder. False with `error` when the
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
