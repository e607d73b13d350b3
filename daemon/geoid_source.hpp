// The EGM96 geoid for sessions that turn the vehicle's MSL altitudes into ellipsoid heights
// themselves (a MAVLink gimbal device without a fixed geoid_undulation_m: the registry's
// Entry::needs_geoid). Opened once at start and shared by every gimbal on the io thread: the
// terrain model's geoid when the terrain section has one, else the grid Debian's proj-data
// ships.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "terrain/elevation_model.hpp"

namespace gimbald {

struct OpenedGeoid {
    // The undulation at a point (SessionSettings::geoid_undulation); empty when there is no
    // grid.
    std::function<std::optional<double>(double lat_deg, double lon_deg)> undulation;
    std::string source;   // the grid file, or "terrain" for the terrain model's
    std::string problem;  // when undulation is empty: why
};

OpenedGeoid open_geoid(const gimbal::terrain::ElevationModel* terrain);

}  // namespace gimbald
