// The camera footprint: where the four image-corner rays meet the ground, modelled as the
// WGS84 ellipsoid raised to a given altitude (contract section 11, STATE
// telemetry.footprint). Pure functions of their arguments.
#pragma once

#include <array>
#include <optional>

#include "geo/attitude.hpp"
#include "geo/vec3.hpp"
#include "geo/wgs84.hpp"

namespace gimbal::geo {

struct LatLon {
    double lat_deg = 0;
    double lon_deg = 0;
};

// A pinhole camera: position, attitude of its frame (x along the line of sight, y to the
// image's right, z to the image's bottom) relative to NED, and full fields of view.
struct CameraPose {
    Lla position;
    Quat camera_to_ned;
    double hfov_deg = 0;
    double vfov_deg = 0;
};

// Orion's line-of-sight frame: the mount attitude (mount -> NED) turned by pan (about the
// mount's down axis) and then tilt (about the turned right axis; negative looks down).
Quat line_of_sight_attitude(const Quat& mount_to_ned, double pan_deg, double tilt_deg);

// Where the ray from `from` along `dir_ecef` (any length) first meets the surface at
// `surface_alt_m` above the ellipsoid. nullopt when it misses (points above the horizon)
// or when `from` is not above that surface.
std::optional<Lla> ray_to_surface(const Lla& from, const Vec3& dir_ecef, double surface_alt_m);

// Corners in image order: top-left, top-right, bottom-right, bottom-left. nullopt when any
// corner ray misses, the fields of view are not in (0, 180) degrees, or an input is not
// finite.
using Footprint = std::array<LatLon, 4>;
std::optional<Footprint> footprint(const CameraPose& camera, double ground_alt_m);

}  // namespace gimbal::geo
