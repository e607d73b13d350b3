#include "geo/attitude.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::geo {

Quat normalized(const Quat& q) {
    const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!(n > 0) || !std::isfinite(n)) return Quat{};
    return {q.w / n, q.x / n, q.y / n, q.z / n};
}

Quat conjugate(const Quat& q) {
    return {q.w, -q.x, -q.y, -q.z};
}

Quat operator*(const Quat& a, const Quat& b) {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
            a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

EulerRad quat_to_euler_rad(const Quat& raw) {
    const Quat q = normalized(raw);
    // Clamp: rounding can push the sine a hair past 1 near the poles.
    const double sin_pitch = std::clamp(2.0 * (q.w * q.y - q.x * q.z), -1.0, 1.0);
    EulerRad e;
    e.pitch_rad = std::asin(sin_pitch);
    if (std::fabs(sin_pitch) > 1.0 - 1e-12) {
        // Gimbal lock: only yaw -/+ roll is defined; put it all in yaw.
        e.roll_rad = 0;
        e.yaw_rad = std::atan2(2.0 * (q.w * q.z - q.x * q.y), 1.0 - 2.0 * (q.x * q.x + q.z * q.z));
        return e;
    }
    e.roll_rad = std::atan2(2.0 * (q.w * q.x + q.y * q.z), 1.0 - 2.0 * (q.x * q.x + q.y * q.y));
    e.yaw_rad = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
    return e;
}

EulerDeg quat_to_euler(const Quat& q) {
    const EulerRad r = quat_to_euler_rad(q);
    return {r.roll_rad * rad2deg, r.pitch_rad * rad2deg, r.yaw_rad * rad2deg};
}

Quat euler_to_quat(const EulerRad& e) {
    const double cr = std::cos(e.roll_rad / 2), sr = std::sin(e.roll_rad / 2);
    const double cp = std::cos(e.pitch_rad / 2), sp = std::sin(e.pitch_rad / 2);
    const double cy = std::cos(e.yaw_rad / 2), sy = std::sin(e.yaw_rad / 2);
    // q = yaw(z) * pitch(y) * roll(x)
    return {cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy};
}

Quat euler_to_quat(const EulerDeg& e) {
    return euler_to_quat(
        EulerRad{e.roll_deg * deg2rad, e.pitch_deg * deg2rad, e.yaw_deg * deg2rad});
}

Vec3 rotate(const Quat& body_to_ned, const Vec3& v) {
    const Quat q = normalized(body_to_ned);
    // v' = v + w t + u x t with t = 2 u x v (u the vector part): q v q* without the products.
    const Vec3 u{q.x, q.y, q.z};
    const Vec3 t = 2.0 * cross(u, v);
    return v + q.w * t + cross(u, t);
}

}  // namespace gimbal::geo
