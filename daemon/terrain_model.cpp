#include "terrain_model.hpp"

namespace gimbal::daemon {

OpenedTerrain open_terrain(const Config& config) {
    OpenedTerrain out;
    if (!config.terrain) return out;
    const terrain::TerrainOptions options(*config.terrain);
    auto opened = terrain::ElevationModel::open(options);
    if (!opened)
        out.problem = Problem{"terrain.files", opened.error().message};
    else
        out.model = std::move(opened).value();
    return out;
}

}  // namespace gimbal::daemon
