// Attitude: unit quaternions [w, x, y, z] that rotate body (or gimbal mount) axes into NED,
// and aerospace Euler angles (ZYX: yaw about down, then pitch about the new east, then roll
// about the new north). Pure functions; angles say their unit in their names.
#pragma once

#include "geo/vec3.hpp"

namespace gimbal::geo {

// Rotation from a body frame to NED. Need not be normalised: every function normalises
// (telemetry quaternions are quantised to 1/32767).
struct Quat {
    double w = 1;
    double x = 0;
    double y = 0;
    double z = 0;
};

struct EulerDeg {
    double roll_deg = 0;
    double pitch_deg = 0;  // -90..90
    double yaw_deg = 0;    // -180..180, clockwise from north
};

struct EulerRad {
    double roll_rad = 0;
    double pitch_rad = 0;
    double yaw_rad = 0;
};

// The quaternion scaled to unit length; the identity for a zero (or non-finite) quaternion.
Quat normalized(const Quat& q);
Quat conjugate(const Quat& q);
// Hamilton product: rotate by b, then by a.
Quat operator*(const Quat& a, const Quat& b);

// At pitch +-90 degrees roll and yaw are not separable; roll is then reported as zero.
EulerRad quat_to_euler_rad(const Quat& q);
EulerDeg quat_to_euler(const Quat& q);
Quat euler_to_quat(const EulerRad& e);
Quat euler_to_quat(const EulerDeg& e);

// v expressed in the body frame -> the same vector in NED.
Vec3 rotate(const Quat& body_to_ned, const Vec3& v);

}  // namespace gimbal::geo
