// The EGM96 geoid: its height N above the WGS84 ellipsoid from the 15-minute grid Debian's
// proj-data ships (egm96_15.gtx), read whole through GDAL (4 MB) and interpolated
// bilinearly. h_ellipsoid = h_msl + N. No downloads: the grid is found on PROJ's search path
// or at /usr/share/proj.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "result/result.hpp"

namespace gimbal::terrain {

class Geoid {
  public:
    // The grid file: PROJ's search path (PROJ_DATA, PROJ_LIB, GDAL's PROJ paths), then
    // /usr/share/proj; names egm96_15.gtx, us_nga_egm96_15.tif. nullopt when none exists.
    static std::optional<std::string> find_egm96();

    // Reads a geoid grid (any GDAL raster on a geographic lattice covering the globe), or
    // unavailable naming the file.
    static Result<Geoid> open(const std::string& path);

    // Geoid height above the ellipsoid (m) at a point; longitudes wrap.
    double undulation(double lat_deg, double lon_deg) const;
    const std::string& path() const { return path_; }

  private:
    std::string path_;
    std::vector<float> values_;
    int width_ = 0, height_ = 0;
    double lon0_ = 0, lat0_ = 0;  // centre of pixel (0, 0)
    double dlon_ = 0, dlat_ = 0;  // dlat negative for north-up grids
};

}  // namespace gimbal::terrain
