// The little geometry the simulator needs on top of lib/geo: rotation matrices, positions in
// radians (the units of the ICD's packets), local NED axes, and where a ray meets flat terrain.
// Angles are radians, distances metres. Body/mount frames are x forward, y right, z down.
#pragma once

#include <array>
#include <cmath>
#include <optional>

#include "geo/attitude.hpp"
#include "geo/vec3.hpp"

namespace gimbal::sim {

using geo::Vec3;

// Unit vector along v; the zero vector stays zero.
inline Vec3 normalized(Vec3 v) {
    const double n = norm(v);
    return n > 0 ? (1.0 / n) * v : Vec3{};
}
// Angle between two directions, 0..pi; 0 when either is the zero vector.
double angle_between(Vec3 a, Vec3 b);

// Rotation matrix, row-major: out = m * v.
struct Mat3 {
    std::array<std::array<double, 3>, 3> m{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
};
Vec3 operator*(const Mat3& r, Vec3 v);
Mat3 transpose(const Mat3& r);
Mat3 operator*(const Mat3& a, const Mat3& b);

// Unit quaternion [w x y z] of the rotation from a body frame to NED.
using geo::Quat;
// Aerospace Euler angles (yaw, then pitch, then roll) of a body frame relative to NED.
Quat quat_from_euler(double roll, double pitch, double yaw);
// Direction cosine matrix of q: v_ned = dcm(q) * v_body.
Mat3 dcm_from_quat(const Quat& q);

// WGS84 geodetic position: latitude and longitude in radians, height above the ellipsoid
// (geo::Lla holds degrees).
struct Lla {
    double lat = 0;
    double lon = 0;
    double alt = 0;
};
Vec3 to_ecef(const Lla& p);
Lla to_lla(Vec3 ecef);

// Rotation from local NED axes at (lat, lon) to ECEF axes: v_ecef = ned_to_ecef(lat, lon) * v_ned.
Mat3 ned_to_ecef(double lat, double lon);

// The first point where the ray origin + s * dir (s > 0) reaches the surface of constant
// ellipsoid height terrain_alt; none when the ray points away from it or starts below it.
std::optional<Vec3> hit_flat_terrain(Vec3 origin_ecef, Vec3 dir_ecef, double terrain_alt);

// Wraps an angle to [-pi, pi).
double wrap_pi(double a);

using geo::pi;
inline constexpr double deg = pi / 180.0;

}  // namespace gimbal::sim
