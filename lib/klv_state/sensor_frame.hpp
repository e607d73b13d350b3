// What gimbald knows about a gimbal's camera, as the KLV it generates (contract section 17):
// a klv::SensorFrame read from the gimbal's typed state - its capabilities
// (session/capabilities.hpp: view, line_of_sight, platform_attitude), never by naming a
// protocol, and the shared telemetry every protocol that has it fills (state/telemetry.hpp:
// `ground`, section 15; `footprint`, sections 11 and 15). Pure: the caller passes the time
// stamp.
//
//   sensor: the view's camera position (MSL) and fields of view;
//   platform heading, pitch, roll: platform_attitude;
//   relative azimuth, elevation, roll: the line of sight in the platform's frame;
//   frame centre: `telemetry.ground` when present (its ellipsoid height to MSL with the
//     view's geoid undulation), else the view's image-centre target;
//   corners: `telemetry.footprint` (top-left, top-right, bottom-right, bottom-left);
//   target location: the track's ground position (its ellipsoid height to MSL with the
//     view's geoid undulation) while a track has one, else the view's target (the gimbal's
//     own);
//   VMTI (tag 74): the track (STATE `track`, when tracking or lost) as one target in pixels
//     of the video's width x height (STATE `video`), track_vmti.hpp; none without a track
//     or before the frame size is known;
//   slant range: the view's measured (laser) range, else `telemetry.ground.range_m`, else
//     the distance from the camera to the frame centre.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "klv/sensor_set.hpp"
#include "session/gimbal_view.hpp"
#include "state/video_state.hpp"

namespace gimbal::klv_state {

// `gimbal.capabilities` must be set; the track is the view's (`gimbal.track`).
klv::SensorFrame sensor_frame(const session::GimbalView& gimbal, std::uint64_t time_us,
                              const std::optional<std::string>& mission_id = std::nullopt);

// Enough to be worth sending: the sensor's position is known.
bool has_position(const klv::SensorFrame& frame);

// STATE `klv_vs_telemetry` (contract section 17): how far the stream's decoded KLV (JSON of
// klv::decode) lies from gimbald's own values, in metres - the sensor position and the frame
// centre, 3D when both altitudes are known, else along the ground; null where either side
// lacks the value. Offsets (tags 26-33) are not compared.
state::KlvOffsets compare(const nlohmann::json& decoded, const klv::SensorFrame& own);

}  // namespace gimbal::klv_state
