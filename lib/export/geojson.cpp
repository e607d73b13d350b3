// RFC 7946: positions are [lon, lat] or [lon, lat, alt] (alt above the WGS84 ellipsoid),
// polygon exterior rings closed and counter-clockwise, one FeatureCollection.
#include <algorithm>

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

Json line_string(const std::vector<const ObjectSample*>& samples) {
    return {
        {"type", "LineString"},
        {"coordinates", coordinates(samples, [](const ObjectSample* s) { return *s->ground; })}};
}

Json optional_text(const std::optional<std::string>& text) {
    return text ? Json(*text) : Json(nullptr);
}

// The object's line, its stretches while lost and its marks (lost, re-acquired, end).
void add_object_track(Json& features, const ObjectTrack& track) {
    const auto line = object_line(track);
    if (line.size() >= 2) {
        const auto lost = std::count_if(line.begin(), line.end(),
                                        [](const ObjectSample* s) { return s->state == "lost"; });
        features.push_back(
            feature(line_string(line), {{"kind", "object_track"},
                                        {"gimbal", track.gimbal},
                                        {"id", track.id},
                                        {"start", iso_time(track.start_us)},
                                        {"end", iso_time(track.end_us)},
                                        {"end_reason", optional_text(track.end_reason)},
                                        {"points", line.size()},
                                        {"lost_points", lost}}));
    }
    for (const auto& stretch : lost_stretches(track))
        features.push_back(
            feature(line_string(stretch), {{"kind", "object_track_lost"},
                                           {"gimbal", track.gimbal},
                                           {"id", track.id},
                                           {"start", iso_time(stretch.front()->time_us)},
                                           {"end", iso_time(stretch.back()->time_us)},
                                           {"points", stretch.size()}}));
    for (const auto& mark : object_marks(track)) {
        const std::vector<Position> at{mark.at};
        features.push_back(
            feature({{"type", "Point"},
                     {"coordinates", coordinates(at, [](const Position& p) { return p; })[0]}},
                    {{"kind", "object_event"},
                     {"gimbal", track.gimbal},
                     {"id", track.id},
                     {"event", mark.event->event},
                     {"time", iso_time(mark.event->time_us)},
                     {"reason", optional_text(mark.event->reason)}}));
    }
}

}  // namespace

std::string to_geojson(const Flight& flight, double footprint_every_s,
                       const std::vector<ObjectTrack>& objects) {
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

    for (const auto& object : objects) add_object_track(features, object);

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
