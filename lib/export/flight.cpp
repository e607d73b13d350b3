#include "export/flight.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "orion/framer.hpp"
#include "state/orion_state.hpp"
#include "state/precision.hpp"
#include "viewpro/json.hpp"
#include "viewpro/output_framer.hpp"

namespace gimbal::flight_export {

namespace {

using nlohmann::json;

std::optional<double> number(const json& j, const char* key) {
    if (!j.is_object()) return std::nullopt;
    const auto it = j.find(key);
    if (it == j.end() || !it->is_number()) return std::nullopt;
    return it->get<double>();
}

void copy(json& to, const char* to_key, const json& from, const char* from_key) {
    if (from.is_object() && from.contains(from_key)) to[to_key] = from[from_key];
}

// One GeolocateTelemetry in STATE form (telemetry_json) -> a track point.
TrackPoint orion_point(std::int64_t time_us, const json& t) {
    TrackPoint p;
    p.time_us = time_us;
    json& v = p.values;
    copy(v, "gimbal_time", t, "utc");
    for (const char* key : {"system_time_ms", "lat", "lon", "alt", "alt_msl", "roll", "pitch",
                            "yaw", "pan", "tilt", "hfov", "vfov", "mode", "range_source"})
        copy(v, key, t, key);
    const auto undulation = number(t, "geoid_undulation");
    const auto lat = number(t, "lat");
    const auto lon = number(t, "lon");
    if (lat && lon) p.aircraft = Position{*lat, *lon, number(t, "alt"), number(t, "alt_msl")};
    const json& target = t.contains("target") ? t["target"] : json();
    if (target.is_object()) {
        copy(v, "target_lat", target, "lat");
        copy(v, "target_lon", target, "lon");
        copy(v, "target_alt", target, "alt");
        const auto alt = number(target, "alt");
        std::optional<double> alt_msl;
        if (alt && undulation) alt_msl = state::metres(*alt - *undulation);
        if (alt_msl) v["target_alt_msl"] = *alt_msl;
        p.target = Position{*number(target, "lat"), *number(target, "lon"), alt, alt_msl};
        const json& corners = t.contains("footprint") ? t["footprint"] : json();
        if (corners.is_array() && corners.size() == 4) {
            std::array<Position, 4> f;
            for (std::size_t i = 0; i < 4; ++i)
                f[i] = Position{number(corners[i], "lat").value_or(0),
                                number(corners[i], "lon").value_or(0), alt, alt_msl};
            p.footprint = f;
        }
    }
    return p;
}

// One decoded Viewpro OUTx -> a track point: pan/tilt are the gimbal's yaw/pitch.
TrackPoint viewpro_point(std::int64_t time_us, const json& o) {
    TrackPoint p;
    p.time_us = time_us;
    json& v = p.values;
    copy(v, "gimbal_time", o, "time");
    const json& uav = o.contains("uav") ? o["uav"] : json();
    const json& gimbal = o.contains("gimbal") ? o["gimbal"] : json();
    const json& target = o.contains("target") ? o["target"] : json();
    copy(v, "lat", uav, "lat");
    copy(v, "lon", uav, "lon");
    copy(v, "alt_msl", uav, "alt_msl");
    for (const char* key : {"roll", "pitch", "yaw"}) copy(v, key, uav, key);
    copy(v, "pan", gimbal, "yaw");
    copy(v, "tilt", gimbal, "pitch");
    copy(v, "mode", o, "format");
    copy(v, "target_lat", target, "lat");
    copy(v, "target_lon", target, "lon");
    copy(v, "target_alt_msl", target, "alt_msl");
    copy(v, "zoom", o, "zoom");
    copy(v, "lrf_m", o, "lrf_m");
    const auto lat = number(uav, "lat");
    const auto lon = number(uav, "lon");
    if (lat && lon) p.aircraft = Position{*lat, *lon, std::nullopt, number(uav, "alt_msl")};
    const auto tlat = number(target, "lat");
    const auto tlon = number(target, "lon");
    // A target at exactly 0,0 is the frame's "no target" (nothing in the Gulf of Guinea).
    if (tlat && tlon && (*tlat != 0 || *tlon != 0))
        p.target = Position{*tlat, *tlon, std::nullopt, number(target, "alt_msl")};
    return p;
}

}  // namespace

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
    if (out.protocol == "orion") {
        orion::Framer framer;
        for (const auto& chunk : stream.chunks) {
            framer.push(chunk.bytes, [&](const orion::Frame& frame) {
                ++out.frames;
                if (frame.id != orion::GeolocateTelemetry::id) return;
                const auto t = orion::decode<orion::GeolocateTelemetry>(frame.data());
                if (!t.ok) {
                    ++out.decode_errors;
                    return;
                }
                out.points.push_back(orion_point(chunk.time_us, state::telemetry_json(t.value)));
            });
        }
        return true;
    }
    if (out.protocol == "viewpro") {
        viewpro::OutputFramer framer;
        for (const auto& chunk : stream.chunks) {
            framer.push(chunk.bytes, [&](const viewpro::OutputFrame& frame) {
                ++out.frames;
                const auto o = viewpro::decode_output(frame);
                if (!o) {
                    ++out.decode_errors;
                    return;
                }
                out.points.push_back(viewpro_point(chunk.time_us, viewpro::to_json(*o)));
            });
        }
        return true;
    }
    error = "gimbal " + stream.gimbal.name + ": unknown protocol (its interface description \"" +
            stream.gimbal.description + "\" names neither orion nor viewpro)";
    return false;
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
