// The simulator's ground: an analytic terrain around the demo area (the simulated Orion
// circles 45.7 N 121.5 W at 1500 m): a rolling plateau, six hills of 300-600 m and a river
// valley some 300 m deep winding east-west south of the circle - roughly the Columbia River
// Gorge's relief, not its shape. Heights are above the WGS84 ellipsoid (the EGM96 geoid lies
// about 21 m below the ellipsoid here), smooth and cheap to evaluate (a few exponentials).
// `sim_terrain_surface` is it on a 1 arc-second lattice: the same surface as the GeoTIFF
// lib/terrain's write_geotiff makes of it at that spacing (gimbal-sim --write-dem), read with
// geoid none. Pure.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geo/footprint.hpp"
#include "geo/sampled_surface.hpp"

namespace gimbal::sim {

// The terrain's origin: x east and y north in metres are measured from here on a local
// equirectangular grid (lat = 45.7 + y / M, lon = -121.5 + x / (N cos 45.7), M and N the WGS84
// radii of curvature at 45.7 N).
inline constexpr double terrain_origin_lat_deg = 45.7;
inline constexpr double terrain_origin_lon_deg = -121.5;
// No point of the terrain is higher (m above the ellipsoid).
inline constexpr double terrain_max_alt_m = 1300;

// Height above the WGS84 ellipsoid (m) at any point.
double terrain_height(double lat_deg, double lon_deg);

// A point on the terrain's local grid: metres east and north of the origin (the rendered
// video's texture and grid lines are laid out on it).
struct TerrainXY {
    double east_m = 0;
    double north_m = 0;
};
TerrainXY terrain_xy(double lat_deg, double lon_deg);
geo::LatLon terrain_lat_lon(TerrainXY p);
// terrain_height at a grid point.
double terrain_height_xy(TerrainXY p);
// The river's centre line along the valley floor: its northing at an easting.
double river_north_m(double east_m);

// Named points the rendered video will draw: on the ground, alt is the terrain's height.
struct Landmark {
    std::string name;
    double lat_deg = 0;
    double lon_deg = 0;
    double alt_m = 0;
};
const std::vector<Landmark>& landmarks();

// The area `gimbal-sim --write-dem` writes (and gimbald's simulator demo reads back): about
// 44 x 47 km around the terrain's origin, edges on whole arc-seconds so the file's lattice is
// terrain_surface()'s.
geo::GeoRect terrain_dem_area();

// The terrain sampled at 1 arc-second (lattice nodes on whole arc-seconds) and interpolated
// bilinearly, as a geo::Surface.
std::unique_ptr<geo::SampledSurface> terrain_surface();

}  // namespace gimbal::sim
