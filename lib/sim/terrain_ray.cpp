#include "sim/terrain_ray.hpp"

#include <algorithm>
#include <cmath>

#include "sim/terrain_grid.hpp"

namespace gimbal::sim {

namespace {

constexpr double wgs84_a = 6378137.0;
constexpr double wgs84_e2 = 6.69437999014e-3;
// The march over the grid's bound stops this close above it; the model's terrain and then
// the exact geometry take over.
constexpr double march_stop_m = 2.0;
constexpr double model_tolerance_m = 0.002;
constexpr double exact_tolerance_m = 0.005;
constexpr int max_march_steps = 4000;
constexpr double max_relax = 1.6;
constexpr int max_solve_steps = 60;

}  // namespace

TerrainRayCaster::TerrainRayCaster(const geo::Lla& from, double max_range_m)
    : from_(from), from_ecef_(geo::lla_to_ecef(from)), max_range_m_(max_range_m) {
    xy0_ = terrain_xy(from.lat_deg, from.lon_deg);
    gap0_ = from.alt_m - terrain_height_xy(xy0_);
    // The terrain grid's axes against true north and east, from 100 m steps on the ground
    // below (where rays end; a step at the viewpoint's height spans less ground).
    constexpr double step = 100;
    const geo::Lla below{from.lat_deg, from.lon_deg, terrain_height_xy(xy0_)};
    const geo::Vec3 below_ecef = geo::lla_to_ecef(below);
    const auto grid_at = [&](geo::Vec3 ned) {
        const geo::Lla p = geo::ecef_to_lla(below_ecef + geo::ned_to_ecef(ned, below));
        return terrain_xy(p.lat_deg, p.lon_deg);
    };
    const TerrainXY n = grid_at({step, 0, 0}), e = grid_at({0, step, 0});
    xn_ = (n.east_m - xy0_.east_m) / step;
    yn_ = (n.north_m - xy0_.north_m) / step;
    xe_ = (e.east_m - xy0_.east_m) / step;
    ye_ = (e.north_m - xy0_.north_m) / step;
    const double s = std::sin(from.lat_deg * geo::deg2rad);
    const double w2 = 1 - wgs84_e2 * s * s;
    const double meridian = wgs84_a * (1 - wgs84_e2) / (w2 * std::sqrt(w2));
    const double normal = wgs84_a / std::sqrt(w2);
    inv_2r_ = 1 / (2 * std::sqrt(meridian * normal));
}

struct TerrainRayCaster::Ray {
    geo::Vec3 d;  // unit, NED at the viewpoint
    geo::Vec3 dir_ecef;
    double down = 0;   // d.z
    double curve = 0;  // the ground falls away as t^2 * curve
    double rate = 0;   // the gap closes no faster than this per metre along the ray
};

double TerrainRayCaster::bound_gap(const Ray& r, double t) const {
    const double n = t * r.d.x, e = t * r.d.y;
    const TerrainXY xy{xy0_.east_m + xn_ * n + xe_ * e, xy0_.north_m + yn_ * n + ye_ * e};
    return from_.alt_m - t * r.down + t * t * r.curve - TerrainGrid::instance().upper_bound(xy);
}

double TerrainRayCaster::model_gap(const Ray& r, double t) const {
    const double n = t * r.d.x, e = t * r.d.y;
    const TerrainXY xy{xy0_.east_m + xn_ * n + xe_ * e, xy0_.north_m + yn_ * n + ye_ * e};
    return from_.alt_m - t * r.down + t * t * r.curve - terrain_height_xy(xy);
}

double TerrainRayCaster::exact_gap(const Ray& r, double t, geo::Lla* at) const {
    const geo::Lla p = geo::ecef_to_lla(from_ecef_ + t * r.dir_ecef);
    if (at) *at = p;
    return p.alt_m - terrain_height(p.lat_deg, p.lon_deg);
}

TerrainRayCaster::Result TerrainRayCaster::hit(const geo::Lla& point, double t) const {
    if (t > max_range_m_) return {};
    return {Status::hit, point, terrain_xy(point.lat_deg, point.lon_deg), t};
}

// Regula falsi (Illinois) on the model's gap; `slope` gets the gap's rate of change there.
double TerrainRayCaster::root(const Ray& r, double t_lo, double g_lo, double t_hi, double g_hi,
                              double* slope) const {
    int side = 0;
    double t = t_hi;
    for (int i = 0; i < max_solve_steps && t_hi - t_lo > 1e-4; ++i) {
        t = t_hi - g_hi * (t_hi - t_lo) / (g_hi - g_lo);
        const double g = model_gap(r, t);
        if (std::abs(g) < model_tolerance_m) break;
        if (g > 0) {
            t_lo = t;
            g_lo = g;
            if (side == 1) g_hi /= 2;
            side = 1;
        } else {
            t_hi = t;
            g_hi = g;
            if (side == -1) g_lo /= 2;
            side = -1;
        }
    }
    // Illinois halves the ends' gaps: measure the slope afresh.
    *slope = model_gap(r, t + 0.5) - model_gap(r, t - 0.5);
    return t;
}

// From the model's crossing to the exact one: Newton steps with the model's slope (the two
// differ by centimetres to metres, and hardly in slope), then a bracketed search if needed.
TerrainRayCaster::Result TerrainRayCaster::exact_root(const Ray& r, double t, double slope) const {
    if (!(slope < 0)) slope = -r.rate;
    geo::Lla at;
    double g = exact_gap(r, t, &at);
    double t_above = 0, t_below = -1;
    for (int i = 0; i < max_solve_steps; ++i) {
        if (std::abs(g) < exact_tolerance_m) return hit(at, t);
        if (g > 0)
            t_above = std::max(t_above, t);
        else if (t_below < 0 || t < t_below)
            t_below = t;
        double next = t - g / slope;
        // Keep inside the bracket once there is one (a bisection step when Newton leaves it).
        if (t_below >= 0 && !(next > t_above && next < t_below)) next = (t_above + t_below) / 2;
        if (!(next > 0)) next = t / 2;
        t = next;
        g = exact_gap(r, t, &at);
    }
    return hit(at, t);
}

TerrainRayCaster::Result TerrainRayCaster::cast(const geo::Vec3& dir_ned) const {
    const double length = geo::norm(dir_ned);
    if (!(length > 0) || !std::isfinite(length)) return {};
    if (!(gap0_ > 0)) return {Status::below, from_, xy0_, 0};
    Ray r;
    r.d = (1 / length) * dir_ned;
    r.dir_ecef = geo::ned_to_ecef(r.d, from_);
    r.down = r.d.z;
    const double level = std::hypot(r.d.x, r.d.y);
    r.curve = level * level * inv_2r_;
    r.rate = r.down + terrain_max_slope * 1.01 * level;
    if (!(r.rate > 1e-9)) return {};  // climbs faster than any slope: never meets the ground

    // Above the highest terrain, start where the ray comes down to it.
    double t = 0;
    const double over = from_.alt_m - terrain_max_alt_m;
    if (over > 0) {
        const double disc = r.down * r.down - 4 * r.curve * over;
        if (r.down <= 0 || disc < 0) return {};
        t = 2 * over / (r.down + std::sqrt(disc));
    }

    // March over the grid's bound in over-relaxed steps (Keinert et al., "Enhanced Sphere
    // Tracing", 2014): max_relax times the safe distance; when the safe intervals before and
    // after a step do not overlap, the step may have crossed ground: take the safe step.
    double t_prev = 0, safe_prev = 0;  // the previous point and its safe distance
    for (int i = 0; i < max_march_steps && t <= max_range_m_; ++i) {
        double gap = bound_gap(r, t);
        if (i > 0 && safe_prev + gap / r.rate < t - t_prev) {
            t = t_prev + safe_prev;
            gap = bound_gap(r, t);
        }
        if (gap < march_stop_m) {
            // Near the ground: the model's own terrain. The bound lies nowhere below it, so
            // the ray is still above the terrain at t_prev.
            double g = model_gap(r, t);
            double slope = 0;
            if (g <= 0) {
                const double g_prev = t_prev == 0 ? gap0_ : model_gap(r, t_prev);
                const double crossing = root(r, t_prev, g_prev, t, g, &slope);
                return exact_root(r, crossing, slope);
            }
            // Still above: step safely, then extrapolate (secant) until the ray is under -
            // or, when it pulls away again (it skims a ridge), go back to marching.
            double t_a = t, g_a = g;
            double t_b = t + g / r.rate;
            bool away = false;
            for (int k = 0; k < max_solve_steps && t_b <= max_range_m_ && !away; ++k) {
                const double g_b = model_gap(r, t_b);
                if (g_b <= 0) {
                    const double crossing = root(r, t_a, g_a, t_b, g_b, &slope);
                    return exact_root(r, crossing, slope);
                }
                if (g_b < model_tolerance_m)
                    return exact_root(r, t_b, model_gap(r, t_b + 0.5) - model_gap(r, t_b - 0.5));
                away = g_b > g_a && g_b > march_stop_m;
                const double safe = t_b + g_b / r.rate;
                // Descending towards the ground: aim where the secant says, a little past it.
                const double aim = g_a > g_b ? t_b + 1.05 * g_b * (t_b - t_a) / (g_a - g_b) : safe;
                t_a = t_b;
                g_a = g_b;
                t_b = std::max(safe, std::min(aim, safe + 50 * g_b / r.rate));
            }
            t_prev = t_a;
            safe_prev = g_a / r.rate;
            t = t_b;
            continue;
        }
        const double alt = from_.alt_m - t * r.down + t * t * r.curve;
        if (alt > terrain_max_alt_m && 2 * t * r.curve >= r.down) return {};  // climbing away
        t_prev = t;
        safe_prev = gap / r.rate;
        t += max_relax * safe_prev;
    }
    return {};
}

}  // namespace gimbal::sim
