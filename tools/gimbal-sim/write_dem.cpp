#include "write_dem.hpp"

#include <iostream>

#include "sim/terrain.hpp"
#include "terrain/geotiff_writer.hpp"

namespace gimbal_sim {

int write_dem(const std::string& path) {
    const auto area = gimbal::sim::terrain_dem_area();
    // 1 arc-second nodes on whole arc-seconds: the lattice of sim::terrain_surface().
    const gimbal::terrain::GridSpec grid{area.lat_min, area.lat_max, area.lon_min, area.lon_max,
                                         1.0 / 3600};
    const std::string error =
        gimbal::terrain::write_geotiff(path, grid, gimbal::sim::terrain_height);
    if (!error.empty()) {
        std::cerr << "gimbal-sim: --write-dem: " << error << std::endl;
        return 2;
    }
    std::cout << "dem: " << path << " (" << gimbal::terrain::grid_cols(grid) << " x "
              << gimbal::terrain::grid_rows(grid) << " nodes, heights above the WGS84 ellipsoid)"
              << std::endl;
    return 0;
}

}  // namespace gimbal_sim
