// The elevation files, opened and read through GDAL (contract section 15): every file is
// checked first (dem_policy.hpp), opened with its one allowed driver, placed on a lattice
// (DemLayout), and read a block of node heights at a time, the geoid added. It holds GDAL
// handles, so one thread at a time uses it: gimbald opens it on the main thread at start and
// then reads only on its terrain loader thread (daemon/terrain_loader.hpp).
//
// Rasters on the same geographic lattice (same pixel size, origins a whole number of pixels
// apart: SRTM tiles, a GeoTIFF cut in pieces) form one lattice, so cells across their edges
// interpolate as in one raster. A raster in a projected CRS becomes its own geographic
// lattice of the same spacing whose nodes are sampled bilinearly from it (points reprojected
// with OGR).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "terrain/block_cache.hpp"
#include "terrain/dem_layout.hpp"
#include "terrain/terrain_config.hpp"

#include "result/result.hpp"

namespace gimbal::terrain {

// The config section `terrain` (terrain_config.hpp) and where the EGM96 grid is.
struct TerrainOptions : TerrainConfig {
    explicit TerrainOptions(TerrainConfig config = {}) : TerrainConfig(std::move(config)) {}
    // The EGM96 grid; empty: Geoid::find_egm96().
    std::string geoid_grid;
};

class DemReader {
  public:
    // Opens every file (globs expanded, sorted). Errors (unavailable) name the file: a path
    // or glob that names no file, a file the policy refuses, a file GDAL cannot read, a
    // raster without usable georeferencing or CRS, a missing geoid grid with geoid egm96.
    static Result<std::unique_ptr<DemReader>> open(const TerrainOptions& options);
    ~DemReader();
    DemReader(const DemReader&) = delete;
    DemReader& operator=(const DemReader&) = delete;

    std::shared_ptr<const DemLayout> layout() const { return layout_; }

    // The block's node heights above the ellipsoid (NaN where unknown), summarised. GDAL asks
    // `keep_going` (when given) as it reads; false abandons the read, and read() returns false.
    bool read(const BlockKey& key, Block& block, const std::function<bool()>& keep_going = {});

    struct Tile;

  private:
    DemReader();
    std::string open_tile(const std::string& path, const std::string& resolved,
                          const std::string& driver, Tile& t);
    void place(std::size_t tile_index);
    bool load_geographic(const DemLattice& l, const BlockKey& key, Block& block);
    bool load_projected(const DemLattice& l, const Tile& t, const BlockKey& key, Block& block);
    bool read_window(const Tile& t, int x, int y, int w, int h);
    double read_value(const Tile& t, float raw) const;

    std::shared_ptr<DemLayout> layout_;
    std::vector<Tile> tiles_;
    std::vector<float> scratch_;
    const std::function<bool()>* keep_going_ = nullptr;  // during read()
};

}  // namespace gimbal::terrain
