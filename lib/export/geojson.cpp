// RFC 7946: positions are [lon, lat] or [lon, lat, alt] (alt above the WGS84 ellipsoid),
// polygon exterior rings closed and counter-clockwise, one FeatureCollection.
#include "export/writers.hpp"

namespace gimbal::flight_export {

namespace {

using Json = nlohmann::ordered_json;

template <class Points, class Get>
Json coordinates(const Points& points, Get get) {
    bool three_d = true;
    for (const auto& p : points) three_d = three_d && get(p).alt.has_value();
    Json out = Json::array();
    for (const auto& p : points) {
        const Position& pos = get(p);
        Json c = {pos.lon, pos.lat};
        if (three_d) c.push_back(*pos.alt);
        out.push_back(std::move(c));
    }
    return out;
}

Json feature(Json geometry, Json properties) {
    return Json{{"type", "Feature"},
                {"geometry", std::move(geometry)},
                {"properties", std::move(properties)}};
}

Json point_properties(const char* kind, const TrackPoint& p) {
    Json props = {{"kind", kind}, {"time", iso_time(p.time_us)}};
    for (const auto& [key, value] : p.values.items()) props[key] = value;
    return props;
}

}  // namespace

std::string to_geojson(const Flight& flight, double footprint_every_s) {
    Json features = Json::array();

    std::vector<const TrackPoint*> track;
    for (const auto& p : flight.points)
        if (p.aircraft) track.push_back(&p);
    if (track.size() >= 2) {
        features.push_back(feature(
            {{"type", "LineString"},
             {"coordinates", coordinates(track, [](const TrackPoint* p) { return *p->aircraft; })}},
            {{"kind", "aircraft_track"},
             {"gimbal", flight.gimbal},
             {"protocol", flight.protocol},
             {"start", iso_time(track.front()->time_us)},
             {"end", iso_time(track.back()->time_us)},
             {"points", track.size()}}));
    }

    for (const auto& segment : target_segments(flight)) {
        if (segment.size() < 2) continue;  // a LineString needs two positions
        features.push_back(feature(
            {{"type", "LineString"},
             {"coordinates", coordinates(segment, [](const TrackPoint* p) { return *p->target; })}},
            {{"kind", "target_track"},
             {"gimbal", flight.gimbal},
             {"start", iso_time(segment.front()->time_us)},
             {"end", iso_time(segment.back()->time_us)},
             {"points", segment.size()}}));
    }

    for (const TrackPoint* p : footprints_every(flight, footprint_every_s)) {
        const auto ring = counter_clockwise_ring(*p->footprint);
        features.push_back(
            feature({{"type", "Polygon"},
                     {"coordinates",
                      Json::array({coordinates(ring, [](const Position& q) { return q; })})}},
                    point_properties("footprint", *p)));
    }

    Json collection = {{"type", "FeatureCollection"}, {"features", std::move(features)}};
    return collection.dump(1) + "\n";
}

}  // namespace gimbal::flight_export
