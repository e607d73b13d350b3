// gimbals[].video.tracking (contract section 20): visual tracking for a gimbal with video -
// which tracker gimbal-track runs, the width frames are scaled to, when a track counts as
// lost and when a lost one ends, and whether gimbald steers the gimbal at the object by
// default. Declared once here as a fields() visit (lib/config/fields.hpp); the ranges are the
// wire protocol's (lib/track/wire/messages.hpp), so every value read can be sent.
#pragma once

#include <array>

#include "config/fields.hpp"
#include "track/wire/messages.hpp"

namespace gimbald::video {

using TrackerKind = gimbal::track::wire::TrackerKind;

struct TrackingConfig {
    // The contract's default; docs/tracking.md measures KCF as the one that meets the CPU
    // budget on a small machine.
    TrackerKind tracker = TrackerKind::csrt;
    int width = 640;            // pixels frames are scaled to before tracking
    double lost_after_s = 1.0;  // no frame for this long: the track is lost
    double reacquire_s = 10;    // lost for this long: the track ends (timeout / no_video)
    bool steer = true;          // the `track` command's `steer` when it gives none
    bool operator==(const TrackingConfig&) const = default;
};

inline constexpr gimbal::config::Range lost_after_range{0.1, 60};
inline constexpr gimbal::config::Range reacquire_range{0, gimbal::track::wire::max_seconds};

inline constexpr std::array<gimbal::config::Named<TrackerKind>, 2> tracker_kind_names{
    {{"csrt", TrackerKind::csrt}, {"kcf", TrackerKind::kcf}}};

template <class V>
void fields(V& v, TrackingConfig& c) {
    v.choice("tracker", c.tracker, tracker_kind_names);
    v.integer("width", c.width, {gimbal::track::wire::min_width, gimbal::track::wire::max_width});
    v.number("lost_after_s", c.lost_after_s, lost_after_range);
    v.number("reacquire_s", c.reacquire_s, reacquire_range);
    v.boolean("steer", c.steer);
}

}  // namespace gimbald::video
