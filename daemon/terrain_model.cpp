#include "terrain_model.hpp"

namespace gimbal::daemon {

OpenedTerrain open_terrain(const Config& config) {
    OpenedTerrain out;
    if (!config.terrain) return out;
    terrain::TerrainOptions options;
    options.files = config.terrain->files;
    options.geoid = config.terrain->geoid == TerrainGeoid::none ? terrain::GeoidModel::none
                                                                : terrain::GeoidModel::egm96;
    options.cache_mb = config.terrain->cache_mb;
    auto opened = terrain::ElevationModel::open(options);
    if (!opened.model)
        out.problem = Problem{"terrain.files", opened.error};
    else
        out.model = std::move(opened.model);
    return out;
}

}  // namespace gimbal::daemon
