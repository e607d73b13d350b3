#include "sim/terrain_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace gimbal::sim {

namespace {

constexpr double spacing_m = 200;
constexpr double half_extent_m = 32000;
constexpr int nodes = static_cast<int>(2 * half_extent_m / spacing_m) + 1;

std::size_t at(int i, int j) {
    return static_cast<std::size_t>(j) * nodes + static_cast<std::size_t>(i);
}

}  // namespace

const TerrainGrid& TerrainGrid::instance() {
    static const TerrainGrid grid;
    return grid;
}

TerrainGrid::TerrainGrid() : heights_(static_cast<std::size_t>(nodes) * nodes) {
    for (int j = 0; j < nodes; ++j)
        for (int i = 0; i < nodes; ++i)
            heights_[at(i, j)] = static_cast<float>(
                terrain_height_xy({i * spacing_m - half_extent_m, j * spacing_m - half_extent_m}));
    // Bilinear interpolation of a smooth surface is worst near cell centres: measure there,
    // with margin for the float samples and the points in between.
    double worst = 0;
    for (int j = 0; j + 1 < nodes; ++j)
        for (int i = 0; i + 1 < nodes; ++i) {
            const double x = (i + 0.5) * spacing_m - half_extent_m;
            const double y = (j + 0.5) * spacing_m - half_extent_m;
            worst = std::max(worst, terrain_height_xy({x, y}) - lookup(x, y));
        }
    error_m_ = 1.5 * worst + 0.5;
}

double TerrainGrid::lookup(double x, double y) const {
    const double u = (x + half_extent_m) / spacing_m, v = (y + half_extent_m) / spacing_m;
    const int i = std::clamp(static_cast<int>(u), 0, nodes - 2);
    const int j = std::clamp(static_cast<int>(v), 0, nodes - 2);
    const double fu = u - i, fv = v - j;
    const double south = heights_[at(i, j)] + fu * (heights_[at(i + 1, j)] - heights_[at(i, j)]);
    const double north =
        heights_[at(i, j + 1)] + fu * (heights_[at(i + 1, j + 1)] - heights_[at(i, j + 1)]);
    return south + fv * (north - south);
}

double TerrainGrid::upper_bound(TerrainXY p) const {
    if (!(std::abs(p.east_m) < half_extent_m && std::abs(p.north_m) < half_extent_m))
        return terrain_height_xy(p);
    return lookup(p.east_m, p.north_m) + error_m_;
}

}  // namespace gimbal::sim
