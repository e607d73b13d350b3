// The daemon's elevation model (contract section 15): one per daemon, opened from the
// `terrain` section at start and by --check-config (terrain files are configuration, not
// devices), shared by every gimbal on the io thread.
#pragma once

#include <memory>
#include <optional>

#include "config.hpp"
#include "terrain/elevation_model.hpp"

namespace gimbal::daemon {

struct OpenedTerrain {
    std::unique_ptr<terrain::ElevationModel> model;  // null without a terrain section
    std::optional<Problem> problem;  // "terrain.files: FILE: what is wrong", when it failed
};

OpenedTerrain open_terrain(const Config& config);

}  // namespace gimbal::daemon
