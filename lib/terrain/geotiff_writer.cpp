#include "terrain/geotiff_writer.hpp"

#include <cmath>
#include <vector>

#include "terrain/gdal_handle.hpp"

namespace gimbal::terrain {

namespace {
constexpr double nodata = -32768;
}

int grid_rows(const GridSpec& s) {
    return static_cast<int>(std::lround((s.lat_max - s.lat_min) / s.spacing_deg)) + 1;
}

int grid_cols(const GridSpec& s) {
    return static_cast<int>(std::lround((s.lon_max - s.lon_min) / s.spacing_deg)) + 1;
}

std::string write_geotiff(const std::string& path, const GridSpec& s,
                          const std::function<double(double, double)>& fn) {
    if (!(s.spacing_deg > 0) || !(s.lat_max > s.lat_min) || !(s.lon_max > s.lon_min) ||
        s.lat_min < -90 || s.lat_max > 90)
        return path + ": invalid grid bounds or spacing";
    gdal_init();
    QuietErrors quiet;
    GDALDriverH driver = GDALGetDriverByName("GTiff");
    if (!driver) return path + ": GDAL has no GTiff driver";
    const int rows = grid_rows(s), cols = grid_cols(s);
    const char* options[] = {"TILED=YES", "COMPRESS=DEFLATE", "BIGTIFF=IF_SAFER", nullptr};
    Dataset ds(
        GDALCreate(driver, path.c_str(), cols, rows, 1, GDT_Float32, const_cast<char**>(options)));
    if (!ds) return path + ": cannot create: " + QuietErrors::message();
    // Pixel-is-area: node (0, 0) is the centre of the top-left pixel.
    double gt[6] = {s.lon_min - s.spacing_deg / 2,
                    s.spacing_deg,
                    0,
                    s.lat_max + s.spacing_deg / 2,
                    0,
                    -s.spacing_deg};
    SpatialRef wgs84 = wgs84_lonlat();
    GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
    if (GDALSetGeoTransform(ds.get(), gt) != CE_None ||
        GDALSetSpatialRef(ds.get(), wgs84.get()) != CE_None ||
        GDALSetRasterNoDataValue(band, nodata) != CE_None)
        return path + ": cannot write georeferencing: " + QuietErrors::message();
    std::vector<float> row(static_cast<std::size_t>(cols));
    for (int r = 0; r < rows; ++r) {
        const double lat = s.lat_max - r * s.spacing_deg;
        for (int c = 0; c < cols; ++c) {
            const double h = fn(lat, s.lon_min + c * s.spacing_deg);
            row[static_cast<std::size_t>(c)] =
                std::isfinite(h) ? static_cast<float>(h) : static_cast<float>(nodata);
        }
        if (GDALRasterIO(band, GF_Write, 0, r, cols, 1, row.data(), cols, 1, GDT_Float32, 0, 0) !=
            CE_None)
            return path + ": cannot write: " + QuietErrors::message();
    }
    GDALDatasetH raw = ds.release();
    GDALClose(raw);
    if (CPLGetLastErrorType() == CE_Failure)
        return path + ": cannot write: " + QuietErrors::message();
    return {};
}

}  // namespace gimbal::terrain
