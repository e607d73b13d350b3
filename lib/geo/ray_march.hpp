// Where a ray first meets a Surface: march along it through the surface's bilinear patches,
// solving the ray against each patch exactly (a quadratic in the distance along the ray), so
// a grazing ray cannot skip a ridge between two samples. Regions whose Bound lies below the
// ray are crossed in one step. Accurate to millimetres against the patches' bilinear surface.
#pragma once

#include "geo/surface.hpp"

namespace gimbal::geo {

Intersection march(Surface& surface, const Lla& from, const Vec3& dir_ecef,
                   const RayOptions& options);

// The distance along a straight lat/lon path from (lat, lon) with rates (dlat, dlon) per
// metre to where it leaves `region` (0 when outside or on its edge heading out; infinity
// when it never does).
double exit_distance(const GeoRect& region, double lat_deg, double lon_deg, double dlat,
                     double dlon);

// lon shifted by whole turns to lie within 180 degrees of ref.
double lon_near(double lon_deg, double ref_deg);

}  // namespace gimbal::geo
