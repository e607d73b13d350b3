// Altitudes left to the terrain (contract section 15): a `geopoint`, or a `path` point,
// without `alt` takes the terrain's height there (above the WGS84 ellipsoid); with
// `alt_ref: "terrain"` its `alt` is the height above the ground (0 when left out). gimbald
// resolves them before the gimbal's protocol plans the command, so every protocol sees plain
// ellipsoid altitudes. Pure apart from what the terrain surface reads.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

#include "command/result.hpp"
#include "geo/surface.hpp"

namespace gimbal::session {

// Does `cmd` take altitudes the terrain may fill (geopoint, path)?
bool takes_ground_altitudes(std::string_view cmd);

// The request with every altitude the terrain was asked for filled in (alt_ref "wgs84"), or
// the request unchanged when it leaves nothing to the terrain (or is malformed in a way the
// planner reports). Errors: bad_request / out_of_range for an alt_ref, or a latitude,
// longitude or height the lookup needs; unavailable when the terrain has no height there or
// none is configured (`terrain` nullptr).
command::Result<nlohmann::json> resolve_ground_altitudes(std::string_view cmd,
                                                         const nlohmann::json& request,
                                                         geo::Surface* terrain);

}  // namespace gimbal::session
