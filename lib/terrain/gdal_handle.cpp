#include "terrain/gdal_handle.hpp"

#include <cpl_error.h>

#include <mutex>

namespace gimbal::terrain {

void gdal_init() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

QuietErrors::QuietErrors() {
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
}

QuietErrors::~QuietErrors() {
    CPLPopErrorHandler();
}

std::string QuietErrors::message() {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? m : "unknown GDAL error";
}

SpatialRef wgs84_lonlat() {
    SpatialRef srs(OSRNewSpatialReference(nullptr));
    OSRSetWellKnownGeogCS(srs.get(), "WGS84");
    OSRSetAxisMappingStrategy(srs.get(), OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

}  // namespace gimbal::terrain
