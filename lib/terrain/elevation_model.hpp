// A digital elevation model (contract section 15): local rasters GDAL reads (GeoTIFF, SRTM
// .hgt, DTED, VRT mosaics of them; dem_policy.hpp says what is refused), heights above EGM96
// converted to the WGS84 ellipsoid (or already ellipsoidal with geoid none), as a
// geo::Surface (bilinear between the raster's nodes, pixel centres) for ray intersection and
// image geometry. Blocks of node heights come through a bounded LRU cache from a BlockSource:
// the files read right away (open()), or - in gimbald - a loader thread that may not have a
// block yet (read_elsewhere()); the block's cells are then unknown for that lookup.
//
// Where rasters overlap, the finest lattice answers first, then the one whose first file
// comes first in `files`; within a lattice, the earlier file (dem_reader.hpp). A node with
// nodata (or outside every raster) is unknown, and so is every cell touching it: unknown,
// never zero. Mosaic projected tiles into one VRT (gdalbuildvrt) so their edges join.
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
#include "terrain/block_source.hpp"
#include "terrain/dem_reader.hpp"
#include "terrain/geoid.hpp"
#include "terrain/terrain_config.hpp"

namespace gimbal::terrain {

class ElevationModel;

struct Elevation {
    double alt_m = 0;                 // above the WGS84 ellipsoid
    std::optional<double> alt_msl_m;  // above EGM96 (nullopt with geoid none)
    std::string source;               // the file whose raster answered
};

class ElevationModel final : public geo::Surface {
  public:
    // Opens every file (DemReader::open: globs expanded, sorted, each checked; errors name
    // the file); blocks are read from the files when first needed.
    static Result<std::unique_ptr<ElevationModel>> open(const TerrainOptions& options);
    ~ElevationModel() override;

    // From now on blocks come from `source` (which must outlive the model's use); returns the
    // files' reader for whoever serves `source` (another thread: the model no longer touches
    // it). Null when it was handed over before.
    std::unique_ptr<DemReader> read_elsewhere(BlockSource& source);

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
    // `misses` counts lookups that met a block the source could not give yet: a caller that
    // sees it grow during a computation knows the terrain was still loading there.
    CacheStats cache_stats() const;

    struct Impl;

  private:
    explicit ElevationModel(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace gimbal::terrain
