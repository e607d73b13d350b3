// STATE telemetry's ground keys (contract sections 11, 15): `footprint` (the image corners on
// the ground), `footprint_surface` ("terrain" or "ellipsoid") and `ground` (where the line of
// sight meets it, beside the gimbal's own `target`). Computed once per telemetry packet by the
// protocol's state model, so a STATE snapshot only copies them.
#pragma once

#include <nlohmann/json.hpp>

#include "geo/ground.hpp"

namespace gimbal::state {

// Sets the three keys in `telemetry` (null where the ground is not met).
void add_ground_keys(nlohmann::json& telemetry, const geo::CameraPose& camera,
                     const geo::Ground& ground);

// {"lat","lon","alt","range_m","surface"} in the precision of contract section 1.
nlohmann::json ground_point_json(const geo::GroundPoint& g);

}  // namespace gimbal::state
