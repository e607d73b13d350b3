// A straight ray in space, described in geodetic coordinates: latitude, longitude and
// ellipsoid height as functions of the distance t along the ray, with their rates. Exact
// conversions at nodes a few kilometres apart and cubic Hermite interpolation between them
// (error well under a millimetre), so marching a ray costs a few multiplications per step
// instead of a geodetic conversion.
#pragma once

#include "geo/vec3.hpp"
#include "geo/wgs84.hpp"

namespace gimbal::geo {

struct RaySample {
    double lat_deg = 0;
    double lon_deg = 0;  // continuous along the ray (not wrapped)
    double alt_m = 0;
    double dlat = 0;   // degrees per metre along the ray
    double dlon = 0;   // degrees per metre
    double dalt = 0;   // metres per metre
    double d2alt = 0;  // per metre
};

class RayPath {
  public:
    // dir_ecef must be finite and non-zero (any length).
    RayPath(const Lla& from, const Vec3& dir_ecef);
    RaySample at(double t_m);
    // The exact point at t (a geodetic conversion).
    Lla exact(double t_m) const;

    static constexpr double node_spacing_m = 5000;

  private:
    struct Node {
        double lat, lon, alt, dlat, dlon, dalt;
    };
    Node node(double t_m) const;

    Vec3 origin_;
    Vec3 dir_;  // unit
    double lon_ref_;
    long segment_ = -1;
    Node a_{}, b_{};
};

}  // namespace gimbal::geo
