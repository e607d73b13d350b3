#include "sim/terrain_ray.hpp"

#include <algorithm>
#include <cmath>

#include "sim/terrain_grid.hpp"

namespace gimbal::sim {

namespace {

constexpr double wgs84_a = 6378137.0;
constexpr double wgs84_e2 = 6.69437999014e-3;
// The tangent-plane march stops this close above the ground; the exact solve takes over.
constexpr double march_stop_m = 2.0;
constexpr double exact_tolerance_m = 0.005;
constexpr int max_march_steps = 4000;
constexpr double max_relax = 1.6;
constexpr int max_solve_steps = 60;

}  // namespace

TerrainRayCaster::TerrainRayCaster(const geo::Lla& from, double max_range_m)
    : from_(from), from_ecef_(geo::lla_to_ecef(from)), max_range_m_(max_range_m) {
    xy0_ = terrain_xy(from.lat_deg, from.lon_deg);
    gap0_ = from.alt_m - terrain_height_xy(xy0_);
    // The terrain grid's axes against true north and east here, from 100 m steps.
    constexpr double step = 100;
    const auto grid_at = [&](geo::Vec3 ned) {
        const geo::Lla p = geo::ecef_to_lla(from_ecef_ + geo::ned_to_ecef(ned, from));
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

double TerrainRayCaster::exact_gap(const geo::Vec3& dir_ecef, double t) const {
    const geo::Lla p = geo::ecef_to_lla(from_ecef_ + t * dir_ecef);
    return p.alt_m - terrain_height(p.lat_deg, p.lon_deg);
}

TerrainRayCaster::Result TerrainRayCaster::hit_at(const geo::Vec3& dir_ecef, double t) const {
    if (t > max_range_m_) return {};
    Result r;
    r.status = Status::hit;
    r.point = geo::ecef_to_lla(from_ecef_ + t * dir_ecef);
    r.xy = terrain_xy(r.point.lat_deg, r.point.lon_deg);
    r.range_m = t;
    return r;
}

// Regula falsi (Illinois) on a bracket: above the ground at t_lo, on or below it at t_hi.
TerrainRayCaster::Result TerrainRayCaster::solve(const geo::Vec3& dir_ecef, double t_lo,
                                                 double g_lo, double t_hi, double g_hi) const {
    int side = 0;
    for (int i = 0; i < max_solve_steps && t_hi - t_lo > 1e-3; ++i) {
        const double t = t_hi - g_hi * (t_hi - t_lo) / (g_hi - g_lo);
        const double g = exact_gap(dir_ecef, t);
        if (std::abs(g) < exact_tolerance_m) return hit_at(dir_ecef, t);
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
    return hit_at(dir_ecef, t_hi);
}

TerrainRayCaster::Result TerrainRayCaster::cast(const geo::Vec3& dir_ned) const {
    const double length = geo::norm(dir_ned);
    if (!(length > 0) || !std::isfinite(length)) return {};
    if (!(gap0_ > 0)) return {Status::below, from_, xy0_, 0};
    const geo::Vec3 d = (1 / length) * dir_ned;
    const geo::Vec3 dir_ecef = geo::ned_to_ecef(d, from_);
    const double down = d.z;
    const double level = std::hypot(d.x, d.y);
    const double curve = level * level * inv_2r_;  // the ground falls away as t^2 * curve
    // The gap closes no faster than this per metre along the ray.
    const double rate = down + terrain_max_slope * 1.01 * level;
    if (!(rate > 1e-9)) return {};  // climbs faster than any slope: never meets the ground

    // Above the highest terrain, start where the ray comes down to it.
    double t = 0;
    const double over = from_.alt_m - terrain_max_alt_m;
    if (over > 0) {
        const double disc = down * down - 4 * curve * over;
        if (down <= 0 || disc < 0) return {};
        t = 2 * over / (down + std::sqrt(disc));
    }

    // Over-relaxed steps (Keinert et al., "Enhanced Sphere Tracing", 2014): step max_relax
    // times the safe distance; when the safe intervals before and after a step do not
    // overlap, the step may have crossed ground: take the safe step instead.
    // The march measures the gap to a grid of the terrain that lies nowhere below it.
    const TerrainGrid& grid = TerrainGrid::instance();
    const auto approx_gap = [&](double at) {
        const double n = at * d.x, e = at * d.y;
        const TerrainXY xy{xy0_.east_m + xn_ * n + xe_ * e, xy0_.north_m + yn_ * n + ye_ * e};
        return from_.alt_m - at * down + at * at * curve - grid.upper_bound(xy);
    };
    double t_prev = 0, safe_prev = 0;  // the previous point and its safe distance
    for (int i = 0; i < max_march_steps && t <= max_range_m_; ++i) {
        double gap = approx_gap(t);
        if (i > 0 && safe_prev + gap / rate < t - t_prev) {
            t = t_prev + safe_prev;
            gap = approx_gap(t);
        }
        if (gap < march_stop_m) {
            // Near the ground: solve on the exact geometry, from a bracket.
            double g = exact_gap(dir_ecef, t);
            if (g <= 0) {
                double g_prev = t_prev == 0 ? gap0_ : exact_gap(dir_ecef, t_prev);
                while (g_prev <= 0 && t_prev > 0) {  // the model was off: back off further
                    t_prev /= 2;
                    g_prev = exact_gap(dir_ecef, t_prev);
                }
                return solve(dir_ecef, t_prev, g_prev, t, g);
            }
            // Still above: step safely, then extrapolate (secant) until the ray is under -
            // or, when it pulls away again (it skims a ridge), go back to marching.
            double t_a = t, g_a = g;
            double t_b = t + g / rate;
            for (int k = 0; k < max_solve_steps && t_b <= max_range_m_; ++k) {
                const double g_b = exact_gap(dir_ecef, t_b);
                if (g_b <= 0) return solve(dir_ecef, t_a, g_a, t_b, g_b);
                if (g_b < exact_tolerance_m) return hit_at(dir_ecef, t_b);
                const bool pulling_away = g_b > g_a && g_b > march_stop_m;
                const double safe = t_b + g_b / rate;
                // Descending towards the ground: aim where the secant says, a little past it.
                const double aim = g_a > g_b ? t_b + 1.05 * g_b * (t_b - t_a) / (g_a - g_b) : safe;
                t_a = t_b;
                g_a = g_b;
                t_b = std::max(safe, std::min(aim, safe + 50 * g_b / rate));
                if (pulling_away) break;
            }
            t_prev = t_a;
            safe_prev = g_a / rate;
            t = t_b;
            continue;
        }
        const double alt = from_.alt_m - t * down + t * t * curve;
        if (alt > terrain_max_alt_m && 2 * t * curve >= down) return {};  // climbing away
        t_prev = t;
        safe_prev = gap / rate;
        t += max_relax * safe_prev;
    }
    return {};
}

}  // namespace gimbal::sim
