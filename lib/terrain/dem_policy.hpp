// What gimbald agrees to read as elevation (contract section 14 v4): local raster files -
// GeoTIFF, SRTM .hgt, DTED - and VRTs over such files inside the configured folders. A DEM is
// configuration written by the operator, but a VRT is a small program for GDAL (raw-file
// bands read any file, pixel functions run code, sources may be URLs or archives) and a
// raster's header may claim any size, so every file is checked here before GDAL reads a
// pixel of it, and `--check-config` refuses the rest by name:
//
// - a regular local file: no FIFO or device, no GDAL virtual file system (/vsicurl/,
//   /vsizip/, ...), no zip archive;
// - its format decided by its content, among GTiff, SRTMHGT, DTED and VRT only (a VRT saved
//   as .tif is a VRT and checked as one);
// - a VRT: sourced bands only (no VRTRawRasterBand, VRTDerivedRasterBand, pixel functions,
//   kernel filters, warped or pansharpened datasets, open options); every source a file that
//   passes these same checks, inside the folders of the configured paths and globs, named
//   absolutely or relative to the VRT, without "..", at most 16 x down-sampled; nested VRTs
//   at most 8 deep and without loops;
// - sizes: at most 2^31 cells, cells of at least 1 mm, blocks of at most 16 MiB.
#pragma once

#include <gdal.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "result/result.hpp"

namespace gimbal::terrain {

namespace dem_limits {
inline constexpr double max_cells = 2147483648.0;  // 2^31
inline constexpr double min_cell_m = 0.001;
inline constexpr std::size_t max_block_bytes = std::size_t{16} << 20;
inline constexpr std::uintmax_t max_vrt_bytes = std::uintmax_t{16} << 20;
inline constexpr int max_vrt_depth = 8;
inline constexpr double max_source_scale = 16;  // source cells per VRT cell, each axis
inline constexpr std::size_t max_sources = 65536;
}  // namespace dem_limits

// The folders a VRT's sources may lie in (or below): each configured path's folder, or a
// glob's up to its first wildcard, resolved (symbolic links followed).
std::vector<std::filesystem::path> dem_folders(const std::vector<std::string>& patterns);

struct CheckedDem {
    std::string path;    // resolved (what GDAL opens)
    std::string driver;  // "GTiff", "SRTMHGT", "DTED" or "VRT", from the content
};

// A configured path or glob that names something other than a local file (a GDAL virtual
// file system, a URL): the problem, naming it; "" when it may be a local file.
std::string check_dem_name(const std::string& pattern);

// Checks a configured file (and, for a VRT, all it names) before GDAL opens it for reading;
// a refusal (unavailable) says why, naming the file as given.
Result<CheckedDem> check_dem_file(const std::string& path,
                                  const std::vector<std::filesystem::path>& folders);

// The size rules on an opened raster, before anything is read from it: "" or the problem
// (without the file's name).
std::string check_raster_size(GDALDatasetH ds);

}  // namespace gimbal::terrain
