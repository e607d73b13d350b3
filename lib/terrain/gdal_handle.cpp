#include "terrain/gdal_handle.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>

#include <algorithm>
#include <array>
#include <mutex>
#include <string_view>

namespace gimbal::terrain {

namespace {

constexpr std::array<const char*, 5> dem_driver_list{"GTiff", "SRTMHGT", "DTED", "VRT", nullptr};
// What else stays registered: the geoid grid's format (egm96_15.gtx).
constexpr std::array<std::string_view, 1> other_drivers{"GTX"};

bool kept(std::string_view name) {
    for (const char* d : dem_driver_list)
        if (d && name == d) return true;
    return std::find(other_drivers.begin(), other_drivers.end(), name) != other_drivers.end();
}

void keep_only_terrain_drivers() {
    for (int i = GDALGetDriverCount() - 1; i >= 0; --i) {
        GDALDriverH driver = GDALGetDriver(i);
        if (kept(GDALGetDriverShortName(driver))) continue;
        GDALDeregisterDriver(driver);
        GDALDestroyDriver(driver);
    }
}

void close_doors() {
    // Side-car files are never looked for: a FIFO named x.tif.aux.xml cannot hang an open.
    CPLSetConfigOption("GDAL_DISABLE_READDIR_ON_OPEN", "EMPTY_DIR");
    CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");
    CPLSetConfigOption("GDAL_VRT_ENABLE_PYTHON", "NO");
    // Should a /vsicurl/ name ever get past the checks (dem_policy), it finds no file and
    // waits at most a second.
    CPLSetConfigOption("CPL_VSIL_CURL_ALLOWED_EXTENSIONS", ".gimbald-no-network");
    CPLSetConfigOption("GDAL_HTTP_TIMEOUT", "1");
    CPLSetConfigOption("GDAL_HTTP_CONNECTTIMEOUT", "1");
    CPLSetConfigOption("GDAL_HTTP_MAX_RETRY", "0");
    OSRSetPROJEnableNetwork(0);
}

}  // namespace

void gdal_init() {
    static std::once_flag once;
    std::call_once(once, [] {
        close_doors();
        GDALAllRegister();
        keep_only_terrain_drivers();
    });
}

const char* const* dem_drivers() {
    return dem_driver_list.data();
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
