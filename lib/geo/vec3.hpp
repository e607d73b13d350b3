// A 3-vector of doubles (ECEF or NED metres, or any other frame the name says).
#pragma once

#include <cmath>

namespace gimbal::geo {

struct Vec3 {
    double x = 0;
    double y = 0;
    double z = 0;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator*(double k, const Vec3& v) {
    return {k * v.x, k * v.y, k * v.z};
}
inline double dot(const Vec3& a, const Vec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3& v) {
    return std::sqrt(dot(v, v));
}

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double deg2rad = pi / 180.0;
inline constexpr double rad2deg = 180.0 / pi;

}  // namespace gimbal::geo
