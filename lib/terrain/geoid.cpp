#include "terrain/geoid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <cpl_string.h>

#include "terrain/gdal_handle.hpp"

namespace gimbal::terrain {

namespace {

void add_path_list(std::vector<std::string>& out, const char* list) {
    if (!list) return;
    std::string s(list);
    std::size_t start = 0;
    while (start <= s.size()) {
        const std::size_t end = std::min(s.find(':', start), s.size());
        if (end > start) out.push_back(s.substr(start, end - start));
        start = end + 1;
    }
}

}  // namespace

std::optional<std::string> Geoid::find_egm96() {
    gdal_init();
    std::vector<std::string> dirs;
    add_path_list(dirs, std::getenv("PROJ_DATA"));
    add_path_list(dirs, std::getenv("PROJ_LIB"));
    if (char** paths = OSRGetPROJSearchPaths()) {
        for (char** p = paths; *p; ++p) dirs.emplace_back(*p);
        CSLDestroy(paths);
    }
    dirs.emplace_back("/usr/share/proj");
    for (const auto& dir : dirs)
        for (const char* name : {"egm96_15.gtx", "us_nga_egm96_15.tif"}) {
            std::error_code ec;
            const auto p = std::filesystem::path(dir) / name;
            if (std::filesystem::is_regular_file(p, ec)) return p.string();
        }
    return std::nullopt;
}

Result<Geoid> Geoid::open(const std::string& path) {
    gdal_init();
    QuietErrors quiet;
    // The grid's own formats only (proj-data ships .gtx; PROJ's CDN .tif), never a VRT.
    const char* const grid_drivers[] = {"GTX", "GTiff", nullptr};
    Dataset ds(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, grid_drivers, nullptr,
                          nullptr));
    if (!ds)
        return Error{code::unavailable, path + ": cannot read the geoid grid: " + quiet.message()};
    double gt[6];
    if (GDALGetGeoTransform(ds.get(), gt) != CE_None || gt[2] != 0 || gt[4] != 0 ||
        GDALGetRasterCount(ds.get()) < 1)
        return Error{code::unavailable, path + ": the geoid grid has no usable georeferencing"};
    Geoid g;
    g.path_ = path;
    g.width_ = GDALGetRasterXSize(ds.get());
    g.height_ = GDALGetRasterYSize(ds.get());
    g.dlon_ = gt[1];
    g.dlat_ = gt[5];
    g.lon0_ = gt[0] + gt[1] / 2;
    g.lat0_ = gt[3] + gt[5] / 2;
    g.values_.resize(static_cast<std::size_t>(g.width_) * static_cast<std::size_t>(g.height_));
    GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
    if (GDALRasterIO(band, GF_Read, 0, 0, g.width_, g.height_, g.values_.data(), g.width_,
                     g.height_, GDT_Float32, 0, 0) != CE_None)
        return Error{code::unavailable, path + ": cannot read the geoid grid: " + quiet.message()};
    return g;
}

double Geoid::undulation(double lat, double lon) const {
    if (values_.empty() || !std::isfinite(lat) || !std::isfinite(lon)) return 0;
    const double y = std::clamp((lat - lat0_) / dlat_, 0.0, static_cast<double>(height_ - 1));
    double x = std::fmod((lon - lon0_) / dlon_, 360.0 / dlon_);
    if (x < 0) x += 360.0 / dlon_;
    const int r = std::min(static_cast<int>(y), height_ - 2);
    const int c = static_cast<int>(x);
    const double fy = y - r, fx = x - c;
    // Columns wrap around the globe (the grid stops one column short of 360 degrees).
    const int c1 = (c + 1) % width_;
    const int c0 = c % width_;
    auto at = [&](int row, int col) {
        return static_cast<double>(
            values_[static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
                    static_cast<std::size_t>(col)]);
    };
    return (1 - fy) * ((1 - fx) * at(r, c0) + fx * at(r, c1)) +
           fy * ((1 - fx) * at(r + 1, c0) + fx * at(r + 1, c1));
}

}  // namespace gimbal::terrain
