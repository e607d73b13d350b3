// Thin ownership and error helpers around GDAL's C API (drivers registered once, GDAL's own
// error printing silenced while we open and read: errors come back as strings instead).
#pragma once

#include <gdal.h>
#include <ogr_srs_api.h>

#include <memory>
#include <string>

namespace gimbal::terrain {

// Registers GDAL's drivers once per process.
void gdal_init();

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

// While alive, GDAL errors are recorded instead of printed; message() is the last one.
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
