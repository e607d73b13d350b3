// The object a visual track followed, as the export formats see it (docs/replay-export.md,
// "The object's track"): one ObjectTrack per track - a track id from its track_start to its
// track_end - with every record of it in order: STATE after each box (where the ground filter
// had the object, how it moved, how sure the tracker was) and the events. Pure.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "export/flight.hpp"
#include "record/track_stream.hpp"
#include "state/track_state.hpp"

namespace gimbal::flight_export {

struct ObjectSample {
    std::int64_t time_us = 0;           // when gimbald handled it
    std::string event;                  // empty for STATE after a box; else the event's name
    std::string state;                  // tracking, lost; "ended" for track_end
    std::optional<std::string> reason;  // track_end
    // STATE's: where the filter had the object (alt above the WGS84 ellipsoid; alt_msl only
    // after with_msl_heights), its velocity, the tracker's confidence, the box's centre.
    std::optional<Position> ground;
    std::optional<state::TrackVelocity> velocity;
    std::optional<double> confidence;
    std::optional<state::TrackCentre> centre;  // also track_start's: its box's
};

struct ObjectTrack {
    std::uint32_t id = 0;
    std::string gimbal;
    std::int64_t start_us = 0;              // its track_start (or its first record)
    std::int64_t end_us = 0;                // its track_end (or its last record)
    std::optional<std::string> end_reason;  // none: the recording ends while it runs
    std::vector<ObjectSample> samples;
};

// The tracks of a recorded track interface, in order. A record of another id than the
// running track's, or any after a track_end, starts a new track (gimbald numbers tracks from
// 1 again when it restarts).
std::vector<ObjectTrack> object_tracks(const record::TrackStream& stream);

// The object's line: every STATE sample with a ground position (predicted while lost), in
// order.
std::vector<const ObjectSample*> object_line(const ObjectTrack& track);

// The stretches while the object was lost: each the located lost samples with the last
// located sample before them and the first after them (so it spans the gap on the line);
// stretches of fewer than two positions are left out.
std::vector<std::vector<const ObjectSample*>> lost_stretches(const ObjectTrack& track);

// Where the object was at its track_lost, track_reacquired and track_end: the latest
// position the filter had before each (events without one are left out).
struct ObjectMark {
    const ObjectSample* event;
    Position at;
};
std::vector<ObjectMark> object_marks(const ObjectTrack& track);

// The tracks with heights above mean sea level (alt_msl, for KML): alt minus the geoid
// undulation the gimbal reported for the aircraft (alt - alt_msl) at the nearest time. A
// flight whose points give no undulation leaves alt_msl empty.
std::vector<ObjectTrack> with_msl_heights(std::vector<ObjectTrack> tracks, const Flight& flight);

// The CSV columns of --format track-csv, in order.
const std::vector<std::string>& object_columns();

}  // namespace gimbal::flight_export
