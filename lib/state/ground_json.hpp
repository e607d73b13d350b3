// A ground point as JSON (the `locate` and `point` replies, contract section 16):
// {"lat","lon","alt","range_m","surface"} in the precision of contract section 1, as STATE
// telemetry's `ground` (state/telemetry.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include "geo/ground.hpp"

namespace gimbal::state {

nlohmann::json ground_point_json(const geo::GroundPoint& g);

}  // namespace gimbal::state
