// Thin ownership and error helpers around GDAL's C API (GDAL set up once, GDAL's own error
// printing silenced while we open and read: errors come back as strings instead).
#pragma once

#include <gdal.h>
#include <ogr_srs_api.h>

#include <memory>
#include <string>

namespace gimbal::terrain {

// Sets GDAL up once per process for local elevation files only (contract section 14 v4):
// registers just the drivers terrain reads - GTiff, SRTMHGT, DTED, VRT, and GTX for the geoid
// grid - so nothing a VRT names can reach another driver (MEM's raw pointers, HTTP, archive
// formats); never lists a raster's folder or reads side-car files (.aux.xml, .ovr, .tfw);
// no Python pixel functions; no network for GDAL's /vsicurl/ or PROJ's grids.
void gdal_init();

// The drivers an elevation file may be read with (GDALOpenEx's allow-list), null-terminated.
const char* const* dem_drivers();

struct DatasetCloser {
    void operator()(void* ds) const { GDALClose(ds); }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;

struct SrsReleaser {
    void operator()(void* srs) const { OSRRelease(srs); }
};
using SpatialRef = std::unique_ptr<void, SrsReleaser>;

struct TransformDestroyer {
    void operator()(void* ct) const { OCTDestroyCoordinateTransformation(ct); }
};
using Transform = std::unique_ptr<void, TransformDestroyer>;

// While alive, GDAL errors (on this thread) are recorded instead of printed; message() is the
// last one.
class QuietErrors {
  public:
    QuietErrors();
    ~QuietErrors();
    QuietErrors(const QuietErrors&) = delete;
    QuietErrors& operator=(const QuietErrors&) = delete;
    static std::string message();
};

// WGS84 longitude/latitude (in that axis order).
SpatialRef wgs84_lonlat();

}  // namespace gimbal::terrain
