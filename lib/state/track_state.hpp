// STATE `track` (contract section 20): the visual track a gimbal runs, null when none - its
// box and centre in section 16 image coordinates, the tracker's confidence, where the object
// is on the ground and how it moves (the ground filter's estimate; null before the first
// located frame), and its life so far. Filled by daemon/track; read back from recordings
// (lib/record/track_records.hpp), hence fields() over a const or non-const part (part.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "state/part.hpp"

namespace gimbal::state {

struct TrackImageBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct TrackCentre {
    double x = 0, y = 0;
};

struct TrackGround {
    double lat = 0, lon = 0, alt = 0;  // degrees, metres above the WGS84 ellipsoid
};

struct TrackVelocity {
    double north = 0, east = 0, speed = 0;  // m/s
    double course = 0;                      // degrees clockwise from true north
};

struct TrackState {
    std::uint32_t id = 0;
    std::string state = "tracking";  // "tracking" or "lost"
    TrackImageBox box;
    TrackCentre centre;
    double confidence = 0;
    std::optional<TrackGround> ground;
    std::optional<TrackVelocity> velocity;
    bool steer = false;
    std::uint64_t frames = 0;
    std::uint64_t lost_frames = 0;
    std::string started_utc;
    double age_s = 0;
};

// Image coordinates: 1e-4 of the half-width is a tenth of a pixel at 4K.
inline constexpr int image_decimals = 4;

template <class V, part_of<TrackImageBox> P>
void fields(V& v, P& b) {
    v.decimals("x0", b.x0, image_decimals);
    v.decimals("y0", b.y0, image_decimals);
    v.decimals("x1", b.x1, image_decimals);
    v.decimals("y1", b.y1, image_decimals);
}

template <class V, part_of<TrackCentre> P>
void fields(V& v, P& c) {
    v.decimals("x", c.x, image_decimals);
    v.decimals("y", c.y, image_decimals);
}

template <class V, part_of<TrackGround> P>
void fields(V& v, P& g) {
    v.latlon("lat", g.lat);
    v.latlon("lon", g.lon);
    v.metres("alt", g.alt);
}

template <class V, part_of<TrackVelocity> P>
void fields(V& v, P& m) {
    v.decimals("north", m.north, 2);
    v.decimals("east", m.east, 2);
    v.decimals("speed", m.speed, 2);
    v.angle("course", m.course);
}

template <class V, part_of<TrackState> P>
void fields(V& v, P& t) {
    v.integer("id", t.id);
    v.string("state", t.state);
    v.object("box", t.box);
    v.object("centre", t.centre);
    v.decimals("confidence", t.confidence, 3);
    v.object("ground", t.ground);
    v.object("velocity", t.velocity);
    v.boolean("steer", t.steer);
    v.integer("frames", t.frames);
    v.integer("lost_frames", t.lost_frames);
    v.string("started_utc", t.started_utc);
    v.seconds("age_s", t.age_s);
}

}  // namespace gimbal::state
