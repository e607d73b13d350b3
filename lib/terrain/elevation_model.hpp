// A digital elevation model (contract section 15): rasters GDAL reads (GeoTIFF, SRTM .hgt,
// DTED, VRT mosaics, ...), heights above EGM96 converted to the WGS84 ellipsoid (or already
// ellipsoidal with geoid none), read in blocks through a bounded LRU cache, as a geo::Surface
// (bilinear between the raster's nodes, pixel centres) for ray intersection and image
// geometry.
//
// Rasters on the same geographic lattice (same pixel size, origins a whole number of pixels
// apart: SRTM tiles, a GeoTIFF cut in pieces) form one lattice, so cells across their edges
// interpolate as in one raster. Where rasters overlap, the finest lattice answers first, then
// the one whose first file comes first in `files`; within a lattice, the earlier file. A
// node with nodata (or outside every raster) is unknown, and so is every cell touching it:
// unknown, never zero. A raster in a projected CRS becomes its own geographic lattice of the
// same spacing whose nodes are sampled bilinearly from it (points reprojected with OGR);
// mosaic projected tiles into one VRT (gdalbuildvrt) so their edges join.
//
// Not thread-safe (the block cache); one io thread uses it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geo/surface.hpp"
#include "terrain/block_cache.hpp"
#include "terrain/geoid.hpp"
#include "terrain/terrain_config.hpp"

namespace gimbal::terrain {

// The config section `terrain` (terrain_config.hpp) and where the EGM96 grid is.
struct TerrainOptions : TerrainConfig {
    explicit TerrainOptions(TerrainConfig config = {}) : TerrainConfig(std::move(config)) {}
    // The EGM96 grid; empty: Geoid::find_egm96().
    std::string geoid_grid;
};

class ElevationModel;
struct OpenedModel {
    std::unique_ptr<ElevationModel> model;
    std::string error;  // when model is null: names the file and what is wrong with it
};

struct Elevation {
    double alt_m = 0;                 // above the WGS84 ellipsoid
    std::optional<double> alt_msl_m;  // above EGM96 (nullopt with geoid none)
    std::string source;               // the file whose raster answered
};

class ElevationModel final : public geo::Surface {
  public:
    // Opens every file (globs expanded, sorted). Errors: a path or glob that names no file,
    // a file GDAL cannot read, a raster without usable georeferencing or CRS, a missing
    // geoid grid with geoid egm96.
    static OpenedModel open(const TerrainOptions& options);
    ~ElevationModel() override;

    geo::SurfaceKind kind() const override { return geo::SurfaceKind::terrain; }
    std::optional<double> height(double lat_deg, double lon_deg) override;
    std::optional<geo::Patch> patch(double lat_deg, double lon_deg, double north,
                                    double east) override;
    std::optional<geo::Bound> bound(double lat_deg, double lon_deg, double north, double east,
                                    double alt_m) override;
    double max_height() const override;

    // Height with the MSL altitude and the answering file (the `elevation` command).
    std::optional<Elevation> elevation(double lat_deg, double lon_deg);
    // EGM96 undulation N at a point (nullopt with geoid none): h_ellipsoid = h_msl + N.
    std::optional<double> geoid_undulation(double lat_deg, double lon_deg) const;

    const std::vector<std::string>& files() const;
    CacheStats cache_stats() const;

    struct Impl;

  private:
    explicit ElevationModel(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace gimbal::terrain
