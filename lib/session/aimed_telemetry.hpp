// STATE telemetry of a gimbal gimbald aims from the aircraft's fix (a MAVLink gimbal device,
// a SIYI camera): such a gimbal reports only its own angles, so the camera's position, the
// aircraft's attitude and where the line of sight meets the ground come from the vehicle feed
// and gimbald's geometry (state::Telemetry's shared keys, contract sections 19 and 22). Pure.
#pragma once

#include <optional>

#include "geo/ground.hpp"
#include "session/capabilities.hpp"
#include "state/telemetry.hpp"
#include "vehicle/aircraft_fix.hpp"

namespace gimbal::session {

// Fills `t`'s lat, lon, alt (the camera, above the ellipsoid), alt_msl, geoid_undulation,
// roll, pitch, yaw (the aircraft's) and view (footprint and ground), and its target where the
// line of sight meets the ground. Returns that point (nullopt: it meets none), for a gimbal
// that knows its target better (a laser range finder).
std::optional<geo::GroundPoint> fill_from_aircraft(state::Telemetry& t,
                                                   const vehicle::AircraftFix& aircraft,
                                                   double geoid_undulation_m,
                                                   const geo::CameraPose& camera,
                                                   const geo::Ground& ground);

// The capabilities' answers read back from that telemetry (nullptr: nothing reported yet).
View view_from(const state::Telemetry* t);
// `line_of_sight`: the camera's, relative to NED; `who` names the gimbal in the message
// ("device", "camera").
command::Result<ImageView> image_from(const state::Telemetry* t,
                                      const std::optional<geo::Quat>& line_of_sight,
                                      std::string_view who);
std::optional<geo::Quat> aircraft_attitude_from(const state::Telemetry* t);

}  // namespace gimbal::session
