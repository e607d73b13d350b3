// Writes a height function as a GeoTIFF through GDAL: a geographic (WGS84) lattice of nodes
// at pixel centres, SRTM-style (nodes on both edges of the bounds), Float32, tiled and
// DEFLATE-compressed. `gimbal-sim --write-dem` and the tests make their DEMs with it.
#pragma once

#include <functional>
#include <string>

namespace gimbal::terrain {

struct GridSpec {
    double lat_min = 0;
    double lat_max = 0;
    double lon_min = 0;
    double lon_max = 0;
    double spacing_deg = 1.0 / 3600;  // 1 arc-second
};

// Rows and columns of nodes the spec gives (both edges included).
int grid_rows(const GridSpec& spec);
int grid_cols(const GridSpec& spec);

// fn returns the height (m) at a node; NaN writes nodata (-32768). Returns an error naming
// the file, or "" on success.
std::string write_geotiff(const std::string& path, const GridSpec& spec,
                          const std::function<double(double lat_deg, double lon_deg)>& fn);

}  // namespace gimbal::terrain
