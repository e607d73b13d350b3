#include "geo/ray_march.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geo/ray_path.hpp"

namespace gimbal::geo {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
// Past a patch's edge by this much (m) so the next lookup lands in the next patch.
constexpr double nudge_m = 1e-4;
// Longest straight-line piece in lat/lon: keeps the linearised path within millimetres.
constexpr double max_piece_m = 500;
// Longest skip over a Bound's region, for the same reason.
constexpr double max_skip_m = 2000;
// The bound must clear the ray by this much (m): covers the path's linearisation.
constexpr double bound_margin_m = 0.01;

bool finite(const Lla& p) {
    return std::isfinite(p.lat_deg) && std::isfinite(p.lon_deg) && std::isfinite(p.alt_m);
}

bool contains(const GeoRect& r, double lat, double lon) {
    const double l = lon_near(lon, (r.lon_min + r.lon_max) / 2);
    return lat >= r.lat_min && lat <= r.lat_max && l >= r.lon_min && l <= r.lon_max;
}

// The smallest root of f0 + f1 s + f2 s^2 in (0, s_max], given f0 > 0.
std::optional<double> first_root(double f0, double f1, double f2, double s_max) {
    auto in_range = [&](double s) { return s > 0 && s <= s_max; };
    if (std::abs(f2) * s_max * s_max <= 1e-12 * (std::abs(f1) * s_max + f0)) {
        if (f1 >= 0) return std::nullopt;
        const double s = -f0 / f1;
        return in_range(s) ? std::optional<double>(s) : std::nullopt;
    }
    const double disc = f1 * f1 - 4 * f2 * f0;
    if (disc < 0) return std::nullopt;
    // Stable form: q and f0 / q are the two roots' numerator and denominator.
    const double q = -0.5 * (f1 + std::copysign(std::sqrt(disc), f1));
    double best = inf;
    for (const double s : {q / f2, q != 0 ? f0 / q : inf})
        if (in_range(s)) best = std::min(best, s);
    return best < inf ? std::optional<double>(best) : std::nullopt;
}

struct Bilinear {
    double a, b, c, d;  // h = a + b u + c v + d u v, u north, v east, in cell units
};

Bilinear coefficients(const Patch& p) {
    return {p.h_sw, p.h_nw - p.h_sw, p.h_se - p.h_sw, p.h_sw - p.h_nw - p.h_se + p.h_ne};
}

}  // namespace

double lon_near(double lon_deg, double ref_deg) {
    return ref_deg + wrap_lon(lon_deg - ref_deg);
}

double exit_distance(const GeoRect& r, double lat, double lon, double dlat, double dlon) {
    const double l = lon_near(lon, (r.lon_min + r.lon_max) / 2);
    double s = inf;
    if (dlat > 0) s = std::min(s, (r.lat_max - lat) / dlat);
    if (dlat < 0) s = std::min(s, (r.lat_min - lat) / dlat);
    if (dlon > 0) s = std::min(s, (r.lon_max - l) / dlon);
    if (dlon < 0) s = std::min(s, (r.lon_min - l) / dlon);
    return std::max(s, 0.0);
}

Intersection march(Surface& surface, const Lla& from, const Vec3& dir, const RayOptions& options) {
    if (!finite(from) || !std::isfinite(norm(dir)) || norm(dir) == 0 || !(options.max_range_m > 0))
        return {RayStatus::invalid, from, 0};
    RayPath path(from, dir);
    const double t_max = options.max_range_m;
    const double top = surface.max_height();
    double t = 0;
    bool first = true;
    // A Bound region the ray is below: no use asking again while it descends inside it.
    // (a flag and a rectangle: GCC 12 at -O3 misreads an optional here)
    bool below = false;
    GeoRect below_bound;
    while (t < t_max) {
        const RaySample r = path.at(t);
        const double lat = r.lat_deg;
        const double lon = wrap_lon(r.lon_deg);
        if (r.dalt >= 0 && r.alt_m > top) return {RayStatus::no_ground, path.exact(t), t};

        if (!(below && r.dalt < 0 && contains(below_bound, lat, lon))) {
            below = false;
            if (const auto b = surface.bound(lat, lon, r.dlat, r.dlon, r.alt_m)) {
                const double clear = r.alt_m - (b->max_alt_m + bound_margin_m);
                if (clear > 0) {
                    // Altitude along a straight ray is convex in t, so the tangent line is a
                    // lower bound: the ray cannot reach the bound's top before clear/-dalt.
                    double step =
                        std::min(exit_distance(b->region, lat, lon, r.dlat, r.dlon), max_skip_m);
                    if (r.dalt < 0) step = std::min(step, clear / -r.dalt);
                    t += std::max(step, nudge_m);
                    first = false;
                    continue;
                }
                below = true;
                below_bound = b->region;
            }
        }

        const auto p = surface.patch(lat, lon, r.dlat, r.dlon);
        if (!p) return {RayStatus::unknown, path.exact(t), t};
        const double l = lon_near(lon, p->lon0 + p->dlon / 2);
        const double s_end =
            std::min({exit_distance(p->region, lat, l, r.dlat, r.dlon), max_piece_m, t_max - t});
        const Bilinear k = coefficients(*p);
        const double u0 = (lat - p->lat0) / p->dlat, du = r.dlat / p->dlat;
        const double v0 = (l - p->lon0) / p->dlon, dv = r.dlon / p->dlon;
        // Ray height minus surface height along the piece: f0 + f1 s + f2 s^2.
        const double f0 = r.alt_m - (k.a + k.b * u0 + k.c * v0 + k.d * u0 * v0);
        const double f1 = r.dalt - (k.b * du + k.c * dv + k.d * (u0 * dv + v0 * du));
        const double f2 = 0.5 * r.d2alt - k.d * du * dv;
        if (f0 <= 0) {
            if (first) return {RayStatus::below_surface, from, 0};
            return {RayStatus::hit, path.exact(t), t};
        }
        if (const auto s = first_root(f0, f1, f2, s_end)) {
            double t_hit = t + *s;
            // One Newton step on the unlinearised path removes what the straight piece and
            // the quadratic altitude left (micrometres in a DEM cell).
            const RaySample h = path.at(t_hit);
            const double hl = lon_near(h.lon_deg, p->lon0 + p->dlon / 2);
            const double u = (h.lat_deg - p->lat0) / p->dlat, v = (hl - p->lon0) / p->dlon;
            const double g = h.alt_m - (k.a + k.b * u + k.c * v + k.d * u * v);
            const double dg =
                h.dalt - ((k.b + k.d * v) * h.dlat / p->dlat + (k.c + k.d * u) * h.dlon / p->dlon);
            if (dg != 0 && std::abs(g / dg) < 1.0) t_hit -= g / dg;
            return {RayStatus::hit, path.exact(t_hit), t_hit};
        }
        t += s_end + nudge_m;
        first = false;
    }
    return {RayStatus::no_ground, path.exact(t_max), t_max};
}

}  // namespace gimbal::geo
