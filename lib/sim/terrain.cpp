#include "sim/terrain.hpp"

#include <array>
#include <cmath>

#include "geo/vec3.hpp"

namespace gimbal::sim {

namespace {

constexpr double wgs84_a = 6378137.0;
constexpr double wgs84_f = 1 / 298.257223563;
constexpr double wgs84_e2 = wgs84_f * (2 - wgs84_f);

struct Radii {
    double meridian, normal_cos;  // m per radian of latitude, of longitude
};

const Radii& radii() {
    static const Radii r = [] {
        const double lat = terrain_origin_lat_deg * geo::deg2rad;
        const double s = std::sin(lat);
        const double w = std::sqrt(1 - wgs84_e2 * s * s);
        return Radii{wgs84_a * (1 - wgs84_e2) / (w * w * w), wgs84_a / w * std::cos(lat)};
    }();
    return r;
}

struct Hill {
    double x, y, height, sigma;  // m east, m north, m, m
};

constexpr std::array<Hill, 6> hills{{
    {2500, 2200, 450, 1400},
    {-3200, 3600, 600, 2000},
    {4200, -4800, 350, 1100},
    {-5200, -2600, 400, 1700},
    {700, 5800, 300, 900},
    {6500, 3800, 500, 2300},
}};

// The river's centre line (y of the valley floor at x) and the valley's shape.
double river_y(double x) {
    return -1800 + 700 * std::sin(x / 4500);
}
constexpr double valley_depth_m = 320;
constexpr double valley_halfwidth_m = 1000;

// Plateau, hills and valley in local metres.
double local_height(double x, double y) {
    double h = 380 + 90 * std::tanh(y / 9000) + 25 * std::sin(x / 2300) * std::cos(y / 3100);
    for (const Hill& hill : hills) {
        const double dx = x - hill.x, dy = y - hill.y;
        h += hill.height * std::exp(-(dx * dx + dy * dy) / (2 * hill.sigma * hill.sigma));
    }
    const double d = (y - river_y(x)) / valley_halfwidth_m;
    return h - valley_depth_m * std::exp(-d * d);
}

double to_lat(double y) {
    return terrain_origin_lat_deg + y / radii().meridian * geo::rad2deg;
}
double to_lon(double x) {
    return terrain_origin_lon_deg + x / radii().normal_cos * geo::rad2deg;
}

}  // namespace

double terrain_height(double lat, double lon) {
    const TerrainXY p = terrain_xy(lat, lon);
    return local_height(p.east_m, p.north_m);
}

TerrainXY terrain_xy(double lat, double lon) {
    return {(lon - terrain_origin_lon_deg) * geo::deg2rad * radii().normal_cos,
            (lat - terrain_origin_lat_deg) * geo::deg2rad * radii().meridian};
}

geo::LatLon terrain_lat_lon(TerrainXY p) {
    return {to_lat(p.north_m), to_lon(p.east_m)};
}

double terrain_height_xy(TerrainXY p) {
    return local_height(p.east_m, p.north_m);
}

double river_north_m(double east_m) {
    return river_y(east_m);
}

const std::vector<Landmark>& landmarks() {
    static const std::vector<Landmark> marks = [] {
        auto mark = [](std::string name, double x, double y) {
            return Landmark{std::move(name), to_lat(y), to_lon(x), local_height(x, y)};
        };
        return std::vector<Landmark>{
            mark("summit", hills[1].x, hills[1].y),
            mark("east_hill", hills[0].x, hills[0].y),
            mark("bridge", 0, river_y(0)),
            mark("radio_mast", -1200, 700),
            mark("farm", 1500, -300),
        };
    }();
    return marks;
}

geo::GeoRect terrain_dem_area() {
    return {45.5, 45.9, -121.8, -121.2};
}

std::unique_ptr<geo::SampledSurface> terrain_surface() {
    return std::make_unique<geo::SampledSurface>(
        terrain_height, geo::Lattice{0, 0, 1.0 / 3600, 1.0 / 3600}, terrain_max_alt_m);
}

}  // namespace gimbal::sim
