// Where rays from one viewpoint first meet the simulator's analytic terrain (sim/terrain.hpp),
// fast enough to cast a few thousand per video frame. Each ray is marched on a tangent-plane
// model of the earth around the viewpoint (curvature included) in steps the terrain's steepest
// slope allows, so it cannot step over a ridge; near the ground the crossing is solved on the
// exact geometry (WGS84 geodetic conversion, terrain_height), so the hit is the analytic
// terrain's, to centimetres - the same ground geo::locate finds on terrain_surface() within the
// 1 arc-second lattice's interpolation (under a metre). Pure.
#pragma once

#include "geo/vec3.hpp"
#include "geo/wgs84.hpp"
#include "sim/terrain.hpp"

namespace gimbal::sim {

// No point of the analytic terrain is steeper than this (rise over run; about 0.39 in fact).
inline constexpr double terrain_max_slope = 0.5;

class TerrainRayCaster {
  public:
    // Rays from `from`; ground farther than max_range_m counts as none.
    explicit TerrainRayCaster(const geo::Lla& from, double max_range_m = 30000);

    enum class Status {
        hit,    // point, xy, range_m are where the ray meets the terrain
        miss,   // no terrain within max range (above the horizon, or too far)
        below,  // the viewpoint is under the terrain
    };
    struct Result {
        Status status = Status::miss;
        geo::Lla point;
        TerrainXY xy;
        double range_m = 0;
    };
    // The ray along dir_ned (NED at the viewpoint, any non-zero length).
    Result cast(const geo::Vec3& dir_ned) const;

    const geo::Lla& from() const { return from_; }
    double max_range_m() const { return max_range_m_; }

  private:
    struct Ray;
    // Height above the ground at t along the ray: on the tangent-plane model, over the march
    // grid's bound or the terrain itself; and on the exact geometry (`at` gets the point).
    double bound_gap(const Ray& ray, double t) const;
    double model_gap(const Ray& ray, double t) const;
    double exact_gap(const Ray& ray, double t, geo::Lla* at = nullptr) const;
    Result hit(const geo::Lla& point, double t) const;
    // Where the ray crosses the model's ground between t_lo (above) and t_hi (on or below);
    // `slope` gets the gap's rate of change there. exact_root goes on from such a crossing
    // to the exact one.
    double root(const Ray& ray, double t_lo, double g_lo, double t_hi, double g_hi,
                double* slope) const;
    Result exact_root(const Ray& ray, double t_model, double slope) const;

    geo::Lla from_;
    geo::Vec3 from_ecef_;
    double max_range_m_;
    TerrainXY xy0_;
    double gap0_ = 0;  // viewpoint height above the terrain
    // Terrain grid metres per metre north / east at the viewpoint.
    double xn_ = 0, xe_ = 1, yn_ = 1, ye_ = 0;
    double inv_2r_ = 0;  // 1 / (2 x the earth's mean radius of curvature here)
};

}  // namespace gimbal::sim
