// gimbal-export's view of an Orion recording: one track point per GeolocateTelemetry, with
// the aircraft, the target and the footprint in STATE form (state::telemetry_json).
#pragma once

#include <memory>

#include "protocols/track.hpp"

namespace gimbal::protocols {

std::unique_ptr<TrackDecoder> make_orion_track_decoder();

// One GeolocateTelemetry in STATE form -> a track point.
TrackPoint orion_track_point(std::int64_t time_us, const nlohmann::json& telemetry);

}  // namespace gimbal::protocols
