// The ground gimbald answers with (contract sections 15 and 16): the terrain where it
// answers, else the flat world - the WGS84 ellipsoid raised to one altitude (the gimbal's own
// target's, when it reports one). The same rule serves STATE's `ground` and `footprint` and
// the `locate` command, so they agree. Pure apart from what a terrain surface reads.
#pragma once

#include <optional>

#include "geo/image.hpp"

namespace gimbal::geo {

// Where gimbald looks for the ground: the terrain (nullptr: none configured) and the flat
// world's altitude (nullopt: unknown, so there is no flat world).
struct Ground {
    Surface* terrain = nullptr;
    std::optional<double> flat_alt_m;
};

struct GroundPoint {
    Lla point;
    double range_m = 0;
    SurfaceKind surface = SurfaceKind::terrain;
};

// The ground seen at an image position: the terrain's hit, else (the ray leaves the terrain's
// coverage, never meets it within range, or starts under it) the flat world's. nullopt when
// neither is met (above the horizon, no flat world) or the camera is invalid; `why` (when
// given) then says the last surface's reason (unknown when there was no surface to try).
std::optional<GroundPoint> locate_ground(const CameraPose& camera, ImagePoint p,
                                         const Ground& ground, RayStatus* why = nullptr);

// The four image corners on the terrain when all four meet it, else on the flat world when
// all four meet that, else nullopt.
std::optional<SurfaceFootprint> ground_footprint(const CameraPose& camera, const Ground& ground);

}  // namespace gimbal::geo
