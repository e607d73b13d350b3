// The analytic terrain sampled every 200 m within 32 km of its origin, for marching rays
// quickly (TerrainRayCaster): a bilinear lookup instead of a dozen exponentials, with a
// bound on how far it can be below the true terrain. Built once, on first use (some tens of
// milliseconds); immutable after, so any thread may read it.
#pragma once

#include <vector>

#include "sim/terrain.hpp"

namespace gimbal::sim {

class TerrainGrid {
  public:
    static const TerrainGrid& instance();

    // A height no lower than terrain_height_xy(p): the grid's (plus its error bound) inside
    // the grid, the exact height outside.
    double upper_bound(TerrainXY p) const;
    double error_bound_m() const { return error_m_; }

  private:
    TerrainGrid();
    double lookup(double x, double y) const;

    std::vector<float> heights_;  // row-major, north rows
    double error_m_ = 0;
};

}  // namespace gimbal::sim
