#include "export/flight.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "protocols/registry.hpp"

namespace gimbal::flight_export {

using nlohmann::json;

const std::vector<std::string>& value_columns() {
    static const std::vector<std::string> columns = {"gimbal_time",
                                                     "system_time_ms",
                                                     "lat",
                                                     "lon",
                                                     "alt",
                                                     "alt_msl",
                                                     "roll",
                                                     "pitch",
                                                     "yaw",
                                                     "pan",
                                                     "tilt",
                                                     "hfov",
                                                     "vfov",
                                                     "mode",
                                                     "range_source",
                                                     "target_lat",
                                                     "target_lon",
                                                     "target_alt",
                                                     "target_alt_msl",
                                                     "zoom",
                                                     "lrf_m"};
    return columns;
}

bool build_flight(const record::GimbalStream& stream, Flight& out, std::string& error) {
    out = Flight{};
    out.gimbal = stream.gimbal.name;
    out.protocol = stream.gimbal.protocol;
    const auto* protocol = protocols::find(out.protocol);
    if (!protocol) {
        error = "gimbal " + stream.gimbal.name +
                ": unknown protocol (its interface description \"" + stream.gimbal.description +
                "\" names none of " + protocols::names_text() + ")";
        return false;
    }
    const auto decoder = protocol->make_track_decoder();
    for (const auto& chunk : stream.chunks) decoder->push(chunk.bytes, chunk.time_us, out.points);
    out.frames = decoder->frames();
    out.decode_errors = decoder->decode_errors();
    return true;
}

std::string value_text(const json& value) {
    if (value.is_null()) return "";
    if (value.is_string()) return value.get<std::string>();
    if (value.is_number_float()) {
        const double v = value.get<double>();
        if (std::isfinite(v) && v == std::trunc(v) && std::fabs(v) < 1e15)
            return std::to_string(static_cast<long long>(v));
    }
    return value.dump();
}

std::string iso_time(std::int64_t time_us) {
    std::int64_t seconds = time_us / 1'000'000;
    std::int64_t micros = time_us % 1'000'000;
    if (micros < 0) {
        micros += 1'000'000;
        --seconds;
    }
    const auto t = static_cast<std::time_t>(seconds);
    std::tm utc{};
    gmtime_r(&t, &utc);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                  utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                  static_cast<int>(micros / 1000));
    return buf;
}

std::vector<const TrackPoint*> footprints_every(const Flight& flight, double every_s) {
    std::vector<const TrackPoint*> chosen;
    for (const auto& p : flight.points) {
        if (!p.footprint) continue;
        if (chosen.empty() || every_s <= 0 ||
            static_cast<double>(p.time_us - chosen.back()->time_us) >= every_s * 1e6)
            chosen.push_back(&p);
    }
    return chosen;
}

std::array<Position, 5> counter_clockwise_ring(const std::array<Position, 4>& corners) {
    // Shoelace in the lon/lat plane: positive area = counter-clockwise.
    double twice_area = 0;
    for (std::size_t i = 0; i < 4; ++i) {
        const auto& a = corners[i];
        const auto& b = corners[(i + 1) % 4];
        twice_area += a.lon * b.lat - b.lon * a.lat;
    }
    std::array<Position, 5> ring;
    for (std::size_t i = 0; i < 4; ++i) ring[i] = twice_area >= 0 ? corners[i] : corners[3 - i];
    ring[4] = ring[0];
    return ring;
}

std::vector<std::vector<const TrackPoint*>> target_segments(const Flight& flight) {
    std::vector<std::vector<const TrackPoint*>> segments;
    bool in_segment = false;
    for (const auto& p : flight.points) {
        if (!p.target) {
            in_segment = false;
            continue;
        }
        if (!in_segment) segments.emplace_back();
        in_segment = true;
        segments.back().push_back(&p);
    }
    return segments;
}

}  // namespace gimbal::flight_export
