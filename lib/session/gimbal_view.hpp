// One gimbal as the daemon's consumers read it - the MAVLink gimbal manager and camera, KLV,
// the image commands (docs/architecture.md "Typed STATE"): what it can do and how it sees,
// through its capabilities bound to its live state; the shared telemetry; its health; its
// video. Typed fields only: STATE's JSON is written at the edges, never read back inside.
// A view of the live state: read it at once (on the io thread), never keep it.
#pragma once

#include <functional>
#include <optional>

#include "session/capabilities.hpp"
#include "state/telemetry.hpp"
#include "state/track_state.hpp"
#include "state/video_state.hpp"

namespace gimbal::session {

struct GimbalView {
    const Capabilities* capabilities = nullptr;   // nullptr: no such gimbal
    const state::Telemetry* telemetry = nullptr;  // nullptr: none yet, or none in its protocol
    bool connected = false;                       // its link
    bool stale = true;                            // no telemetry within stale_after_s
    // Its video (STATE `video`), asked only when needed; empty, or nullopt: no video section.
    std::function<std::optional<state::VideoState>()> video;
    // Its visual track (STATE `track`, contract section 20): empty when the gimbal has no
    // video.tracking; nullopt while no track runs.
    std::function<std::optional<state::TrackState>()> track;
};

}  // namespace gimbal::session
