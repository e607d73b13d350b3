// A protocol's export hook: the track points (aircraft, target, footprint) one telemetry
// frame of a recording holds, for gimbal-export's GeoJSON, KML and CSV. Pure.
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <vector>

namespace gimbal::protocols {

struct TrackPosition {
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
    std::optional<TrackPosition> aircraft;
    std::optional<TrackPosition> target;
    // Image corners on the ground (top-left, top-right, bottom-right, bottom-left), at the
    // target's altitude, when the gimbal reports a field of view.
    std::optional<std::array<TrackPosition, 4>> footprint;
};

class TrackDecoder {
  public:
    virtual ~TrackDecoder() = default;
    // Bytes the gimbal sent, received at time_us: appends one point per telemetry frame.
    virtual void push(std::span<const std::uint8_t> bytes, std::int64_t time_us,
                      std::vector<TrackPoint>& out) = 0;
    virtual std::uint64_t frames() const = 0;         // valid frames seen
    virtual std::uint64_t decode_errors() const = 0;  // valid frames that did not decode
};

}  // namespace gimbal::protocols
