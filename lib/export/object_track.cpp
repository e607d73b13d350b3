#include "export/object_track.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <variant>

#include "state/precision.hpp"

namespace gimbal::flight_export {

namespace {

using record::TrackEvent;
using state::TrackState;

// The state a track is in after the event.
std::string state_after(std::string_view event) {
    if (event == "track_lost") return "lost";
    if (event == "track_end") return "ended";
    return "tracking";  // track_start, track_reacquired
}

ObjectSample sample_of(std::int64_t time_us, const TrackEvent& e) {
    ObjectSample s;
    s.time_us = time_us;
    s.event = e.event;
    s.state = state_after(e.event);
    s.reason = e.reason;
    if (e.box) {  // as STATE writes a centre
        const auto centre = [](double a, double b) {
            return state::round_decimals((a + b) / 2, state::image_decimals);
        };
        s.centre = state::TrackCentre{centre(e.box->x0, e.box->x1), centre(e.box->y0, e.box->y1)};
    }
    return s;
}

ObjectSample sample_of(std::int64_t time_us, const TrackState& t) {
    ObjectSample s;
    s.time_us = time_us;
    s.state = t.state;
    // A non-finite number was written as null and read back as NaN: no position.
    if (t.ground && std::isfinite(t.ground->lat) && std::isfinite(t.ground->lon)) {
        s.ground = Position{t.ground->lat, t.ground->lon, std::nullopt, std::nullopt};
        if (std::isfinite(t.ground->alt)) s.ground->alt = t.ground->alt;
    }
    s.velocity = t.velocity;
    s.confidence = t.confidence;
    s.centre = t.centre;
    return s;
}

std::uint32_t id_of(const record::TrackRecord& r) {
    return std::visit([](const auto& what) { return what.id; }, r.what);
}

const TrackEvent* event_of(const record::TrackRecord& r) {
    return std::get_if<TrackEvent>(&r.what);
}

}  // namespace

std::vector<ObjectTrack> object_tracks(const record::TrackStream& stream) {
    std::vector<ObjectTrack> tracks;
    bool running = false;  // tracks.back() has not ended
    for (const auto& r : stream.records) {
        const TrackEvent* event = event_of(r);
        const auto id = id_of(r);
        if (!running || tracks.back().id != id || (event && event->event == "track_start")) {
            tracks.push_back({id, stream.gimbal, r.time_us, r.time_us, std::nullopt, {}});
            running = true;
        }
        auto& track = tracks.back();
        track.samples.push_back(
            std::visit([&](const auto& what) { return sample_of(r.time_us, what); }, r.what));
        track.end_us = r.time_us;
        if (event && event->event == "track_end") {
            track.end_reason = event->reason;
            running = false;
        }
    }
    return tracks;
}

std::vector<const ObjectSample*> object_line(const ObjectTrack& track) {
    std::vector<const ObjectSample*> line;
    for (const auto& s : track.samples)
        if (s.event.empty() && s.ground) line.push_back(&s);
    return line;
}

std::vector<std::vector<const ObjectSample*>> lost_stretches(const ObjectTrack& track) {
    const auto line = object_line(track);
    std::vector<std::vector<const ObjectSample*>> stretches;
    for (std::size_t i = 0; i < line.size();) {
        if (line[i]->state != "lost") {
            ++i;
            continue;
        }
        std::vector<const ObjectSample*> stretch;
        if (i > 0) stretch.push_back(line[i - 1]);
        while (i < line.size() && line[i]->state == "lost") stretch.push_back(line[i++]);
        if (i < line.size()) stretch.push_back(line[i]);
        if (stretch.size() >= 2) stretches.push_back(std::move(stretch));
    }
    return stretches;
}

std::vector<ObjectMark> object_marks(const ObjectTrack& track) {
    std::vector<ObjectMark> marks;
    const Position* latest = nullptr;
    for (const auto& s : track.samples) {
        if (s.event.empty()) {
            if (s.ground) latest = &*s.ground;
        } else if (s.event != "track_start" && latest) {
            marks.push_back({&s, *latest});
        }
    }
    return marks;
}

std::vector<ObjectTrack> with_msl_heights(std::vector<ObjectTrack> tracks, const Flight& flight) {
    std::vector<std::pair<std::int64_t, double>> undulations;  // (time, alt - alt_msl)
    for (const auto& p : flight.points)
        if (p.aircraft && p.aircraft->alt && p.aircraft->alt_msl)
            undulations.emplace_back(p.time_us, *p.aircraft->alt - *p.aircraft->alt_msl);
    if (undulations.empty()) return tracks;
    std::stable_sort(undulations.begin(), undulations.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    const auto nearest = [&](std::int64_t t) {
        auto after = std::lower_bound(undulations.begin(), undulations.end(), t,
                                      [](const auto& u, std::int64_t v) { return u.first < v; });
        if (after == undulations.end()) return undulations.back().second;
        if (after == undulations.begin()) return after->second;
        const auto before = std::prev(after);
        return t - before->first <= after->first - t ? before->second : after->second;
    };
    for (auto& track : tracks)
        for (auto& s : track.samples)
            if (s.ground && s.ground->alt)
                s.ground->alt_msl = state::metres(*s.ground->alt - nearest(s.time_us));
    return tracks;
}

const std::vector<std::string>& object_columns() {
    static const std::vector<std::string> columns = {
        "time",           "gimbal",        "id",       "event",
        "state",          "lat",           "lon",      "alt",
        "velocity_north", "velocity_east", "speed",    "course",
        "confidence",     "centre_x",      "centre_y", "reason"};
    return columns;
}

}  // namespace gimbal::flight_export
