// gimbal-sim --write-dem FILE: the simulator's analytic terrain (lib/sim/terrain.hpp) as a
// GeoTIFF through GDAL (lib/terrain's writer), so gimbald's `terrain` section, the demo and
// the tests read a real DEM file.
#pragma once

#include <string>

namespace gimbal_sim {

// Writes the DEM; returns the exit status (0, or 2 with the reason on standard error).
int write_dem(const std::string& path);

}  // namespace gimbal_sim
