// The ground as gimbald sees it: a surface of ellipsoid heights over latitude and longitude,
// made of bilinear patches (a DEM's cells, an analytic function sampled on a lattice, or the
// ellipsoid raised to one altitude), and where a ray first meets it (contract section 15).
// The same intersection and image-geometry code runs on every kind. Pure apart from what an
// implementation reads (lib/terrain reads DEM files); not thread-safe: a surface may cache.
#pragma once

#include <optional>
#include <string_view>

#include "geo/vec3.hpp"
#include "geo/wgs84.hpp"

namespace gimbal::geo {

// What a located point lies on (STATE telemetry.footprint_surface, locate's "surface").
enum class SurfaceKind { terrain, ellipsoid };
std::string_view to_string(SurfaceKind kind);

// A latitude/longitude rectangle in degrees (min <= max).
struct GeoRect {
    double lat_min = 0;
    double lat_max = 0;
    double lon_min = 0;
    double lon_max = 0;
};

// One bilinear patch: the heights at the four nodes of a lattice cell (south-west corner
// lat0/lon0, size dlat x dlon degrees), answering over `region` (the cell, or the part of it
// where no higher-priority model answers).
struct Patch {
    GeoRect region;
    double lat0 = 0;
    double lon0 = 0;
    double dlat = 1;
    double dlon = 1;
    double h_sw = 0;
    double h_se = 0;
    double h_nw = 0;
    double h_ne = 0;

    // Ellipsoid height at a point of the cell (extrapolates outside it).
    double at(double lat_deg, double lon_deg) const;
};

// A region around a point where every point of the surface is known and none is higher
// than max_alt_m: the intersection skips it while the ray stays above.
struct Bound {
    GeoRect region;
    double max_alt_m = 0;
};

enum class RayStatus {
    hit,            // point and range_m are where the ray meets the surface
    unknown,        // the ray reached ground the model does not cover (point: where)
    no_ground,      // above the horizon, or no ground within max range (point: where it ended)
    below_surface,  // the ray starts below (or on) the surface
    invalid,        // a non-finite input or a zero direction
};
std::string_view to_string(RayStatus status);

struct Intersection {
    RayStatus status = RayStatus::invalid;
    Lla point;
    double range_m = 0;
};

struct RayOptions {
    double max_range_m = 50000;
};

class Surface {
  public:
    virtual ~Surface() = default;
    virtual SurfaceKind kind() const = 0;
    // Ellipsoid height (m), nullopt where the surface is unknown.
    virtual std::optional<double> height(double lat_deg, double lon_deg) = 0;
    // The patch answering at the point; on a cell edge, the one a ray heading (north, east)
    // enters. nullopt where unknown. Longitudes may be given in any turn (wrapped here).
    virtual std::optional<Patch> patch(double lat_deg, double lon_deg, double north,
                                       double east) = 0;
    // An optional bound around the point for skipping (see Bound); nullopt: none here. A
    // surface with bounds at several scales returns the largest one below `alt_m` (the
    // ray's altitude there), else its smallest.
    virtual std::optional<Bound> bound(double lat_deg, double lon_deg, double north, double east,
                                       double alt_m);
    // No point of the surface is higher (m above the ellipsoid): a rising ray above it never
    // comes down.
    virtual double max_height() const = 0;
    // Where the ray from `from` along `dir_ecef` (any length) first meets the surface. The
    // default marches the ray through the patches (geo/ray_march.hpp).
    virtual Intersection intersect(const Lla& from, const Vec3& dir_ecef,
                                   const RayOptions& options);
};

// The WGS84 ellipsoid raised to one altitude: gimbald's flat world when no terrain is
// configured. Its intersection is closed-form (ray_to_surface), with no range limit.
class EllipsoidSurface final : public Surface {
  public:
    explicit EllipsoidSurface(double alt_m) : alt_m_(alt_m) {}
    SurfaceKind kind() const override { return SurfaceKind::ellipsoid; }
    std::optional<double> height(double, double) override { return alt_m_; }
    std::optional<Patch> patch(double lat_deg, double lon_deg, double north, double east) override;
    double max_height() const override { return alt_m_; }
    Intersection intersect(const Lla& from, const Vec3& dir_ecef,
                           const RayOptions& options) override;

  private:
    double alt_m_;
};

// Longitude in [-180, 180).
double wrap_lon(double lon_deg);

}  // namespace gimbal::geo
