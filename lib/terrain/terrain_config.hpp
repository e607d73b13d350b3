// `terrain` (contract section 15, docs/terrain.md): the elevation models; off unless set.
// Declared once here and read and written by the generic reader (lib/config/fields.hpp);
// TerrainOptions derives from it. The files are opened at start and by --check-config
// (daemon/terrain_model.hpp), not while reading.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "config/fields.hpp"

namespace gimbal::terrain {

enum class GeoidModel { egm96, none };

struct TerrainConfig {
    std::vector<std::string> files;  // paths or globs, as written (relative: to the working dir)
    GeoidModel geoid = GeoidModel::egm96;
    int cache_mb = 64;
    bool operator==(const TerrainConfig&) const = default;
};

inline constexpr std::array<config::Named<GeoidModel>, 2> geoid_model_names{
    {{"egm96", GeoidModel::egm96}, {"none", GeoidModel::none}}};

template <class V>
void fields(V& v, TerrainConfig& c) {
    v.string_list(
        "files", c.files, [](const std::string& file) { return !file.empty(); },
        "must be a non-empty array of paths or globs",
        "must be a path or glob, e.g. \"/var/lib/gimbald/dem/*.tif\"", config::Presence::required,
        true);
    v.choice("geoid", c.geoid, geoid_model_names);
    v.integer("cache_mb", c.cache_mb, {1, 65536});
}

}  // namespace gimbal::terrain
