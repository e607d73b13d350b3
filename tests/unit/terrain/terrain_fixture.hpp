// Helpers for the terrain tests: a temporary directory, GeoTIFFs written from analytic
// functions through GDAL, and the exact first intersection of a ray with a surface found
// independently of the marcher (exact geodetic conversions, steps no longer than the
// surface's slope allows, then bisection).
#pragma once

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "geo/sampled_surface.hpp"
#include "geo/surface.hpp"
#include "geo/wgs84.hpp"
#include "terrain/elevation_model.hpp"
#include "terrain/geotiff_writer.hpp"

namespace terrain_test {

using namespace gimbal;

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        char tmpl[] = "/tmp/unit_terrain.XXXXXX";
        path = mkdtemp(tmpl);
    }
    ~TempDir() { std::filesystem::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

// Local metres east/north of 45.7 N 121.5 W (a plain approximation: the functions only need
// to be smooth and known).
inline double east_m(double lon) {
    return (lon + 121.5) * 77900;
}
inline double north_m(double lat) {
    return (lat - 45.7) * 111130;
}

// The demo area, 0.4 x 0.4 degrees at 1 arc-second.
inline terrain::GridSpec demo_grid(double spacing = 1.0 / 3600) {
    return {45.5, 45.9, -121.7, -121.3, spacing};
}

inline std::unique_ptr<terrain::ElevationModel> open_model(
    std::vector<std::string> files, terrain::GeoidModel geoid = terrain::GeoidModel::none,
    int cache_mb = 64) {
    terrain::TerrainOptions o;
    o.files = std::move(files);
    o.geoid = geoid;
    o.cache_mb = cache_mb;
    auto opened = terrain::ElevationModel::open(o);
    if (!opened) throw std::runtime_error(opened.error().message);
    return std::move(opened).value();
}

struct Exact {
    geo::RayStatus status = geo::RayStatus::no_ground;
    double range_m = 0;
};

// max_slope bounds the surface's height change per metre of ground distance.
inline Exact exact_intersection(geo::Surface& s, const geo::Lla& from, const geo::Vec3& dir,
                                double max_range, double max_slope, double min_step = 0.05) {
    const geo::Vec3 p0 = geo::lla_to_ecef(from);
    const geo::Vec3 d = (1.0 / geo::norm(dir)) * dir;
    auto f = [&](double t) -> std::optional<double> {
        const geo::Lla p = geo::ecef_to_lla(p0 + t * d);
        const auto h = s.height(p.lat_deg, p.lon_deg);
        if (!h) return std::nullopt;
        return p.alt_m - *h;
    };
    auto f0 = f(0);
    if (!f0) return {geo::RayStatus::unknown, 0};
    if (*f0 <= 0) return {geo::RayStatus::below_surface, 0};
    double t = 0, ft = *f0;
    while (t < max_range) {
        // The ray's height above the surface falls by at most (1 + slope) per metre.
        const double step = std::max(min_step, ft / (1 + max_slope) * 0.9);
        const double tn = std::min(t + step, max_range);
        const auto fn = f(tn);
        if (!fn) return {geo::RayStatus::unknown, tn};
        if (*fn <= 0) {
            double lo = t, hi = tn;
            for (int i = 0; i < 60; ++i) {
                const double mid = (lo + hi) / 2;
                const auto fm = f(mid);
                if (fm && *fm > 0)
                    lo = mid;
                else
                    hi = mid;
            }
            return {geo::RayStatus::hit, (lo + hi) / 2};
        }
        t = tn;
        ft = *fn;
    }
    return {geo::RayStatus::no_ground, max_range};
}

// Distance in metres between two points.
inline double distance_m(const geo::Lla& a, const geo::Lla& b) {
    return geo::norm(geo::lla_to_ecef(a) - geo::lla_to_ecef(b));
}

// A direction from `from` to a point at ground distance `dist` along azimuth `az_deg`, at
// height `alt`.
inline geo::Vec3 towards(const geo::Lla& from, double az_deg, double dist, double alt) {
    const double lat = from.lat_deg + dist * std::cos(az_deg * geo::deg2rad) / 111130;
    const double lon = from.lon_deg + dist * std::sin(az_deg * geo::deg2rad) / 77900;
    return geo::lla_to_ecef({lat, lon, alt}) - geo::lla_to_ecef(from);
}

}  // namespace terrain_test
