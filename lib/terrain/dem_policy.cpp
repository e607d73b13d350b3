#include "terrain/dem_policy.hpp"

#include <cpl_string.h>
#include <strings.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>

#include "terrain/gdal_handle.hpp"
#include "terrain/vrt_contents.hpp"

namespace gimbal::terrain {

namespace fs = std::filesystem;

namespace {

constexpr double metres_per_degree = 111320;  // at the equator: no cell is smaller there

bool starts_with_ci(std::string_view s, std::string_view prefix) {
    return s.size() >= prefix.size() && strncasecmp(s.data(), prefix.data(), prefix.size()) == 0;
}

bool ends_with_ci(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() &&
           strncasecmp(s.data() + s.size() - suffix.size(), suffix.data(), suffix.size()) == 0;
}

bool has_wildcard(const std::string& s) {
    return s.find_first_of("*?[") != std::string::npos;
}

bool inside(const fs::path& file, const std::vector<fs::path>& folders) {
    return std::any_of(folders.begin(), folders.end(), [&](const fs::path& folder) {
        const fs::path rel = file.lexically_relative(folder);
        return !rel.empty() && *rel.begin() != "..";
    });
}

std::string folder_list(const std::vector<fs::path>& folders) {
    std::string out;
    for (const auto& f : folders) out += (out.empty() ? "" : ", ") + f.string();
    return out;
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

std::string read_small_file(const fs::path& path, std::string& error) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (ec) {
        error = "cannot read: " + ec.message();
        return {};
    }
    if (size > dem_limits::max_vrt_bytes) {
        error = "a VRT of " + std::to_string(size) + " bytes (at most 16 MiB)";
        return {};
    }
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) error = "cannot read";
    return text;
}

class Checker {
  public:
    explicit Checker(const std::vector<fs::path>& folders) : folders_(folders) {}

    // A file named in the configuration (depth 0) or by a VRT; the error names nothing above
    // it (the caller prefixes its own name).
    std::string file(const std::string& given, int depth, CheckedDem* out = nullptr);

  private:
    std::string vrt(const fs::path& path, int depth);
    std::string source(const VrtSource& s, const fs::path& vrt_dir, int depth);

    const std::vector<fs::path>& folders_;
    std::vector<fs::path> open_vrts_;  // the VRTs being checked, outermost first
    std::set<fs::path> accepted_;
    std::size_t sources_ = 0;
};

std::string not_local(const std::string& name) {
    if (starts_with_ci(name, "/vsi"))
        return "GDAL virtual file systems (/vsicurl/, /vsizip/, ...) are not read: terrain "
               "files are local";
    if (name.find("://") != std::string::npos) return "a URL: terrain files are local";
    return {};
}

std::string Checker::file(const std::string& given, int depth, CheckedDem* out) {
    if (auto e = not_local(given); !e.empty()) return e;
    std::error_code ec;
    const auto status = fs::status(given, ec);
    if (!fs::exists(status)) return "no such file";
    if (!fs::is_regular_file(status))
        return "not a regular file (a folder, FIFO or device): terrain files are regular files";
    const fs::path path = fs::canonical(given, ec);
    if (ec) return "cannot resolve: " + ec.message();
    if (depth > 0 && !inside(path, folders_))
        return "outside the terrain folders (" + folder_list(folders_) + ")";
    if (ends_with_ci(path.string(), ".zip")) return "a zip archive: unzip it first";
    GDALDriverH driver = nullptr;
    {
        QuietErrors quiet;
        driver = GDALIdentifyDriverEx(path.c_str(), GDAL_OF_RASTER, dem_drivers(), nullptr);
    }
    if (!driver) return "not a GeoTIFF, SRTM .hgt, DTED or VRT file";
    const std::string name = GDALGetDriverShortName(driver);
    if (out) *out = {path.string(), name};
    if (accepted_.count(path)) return {};
    if (name == "VRT")
        if (auto e = vrt(path, depth); !e.empty()) return e;
    if (depth > 0) {  // a source: its size here (the configured files' when they are opened)
        QuietErrors quiet;
        const char* const allowed[] = {name.c_str(), nullptr};
        Dataset ds(
            GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, allowed, nullptr, nullptr));
        if (!ds) return "cannot read: " + QuietErrors::message();
        if (auto e = check_raster_size(ds.get()); !e.empty()) return e;
    }
    accepted_.insert(path);
    return {};
}

std::string Checker::vrt(const fs::path& path, int depth) {
    if (std::find(open_vrts_.begin(), open_vrts_.end(), path) != open_vrts_.end())
        return "a VRT that names itself (a loop)";
    if (depth >= dem_limits::max_vrt_depth) return "VRTs nested more than 8 deep";
    std::string error;
    const std::string xml = read_small_file(path, error);
    if (!error.empty()) return error;
    const VrtContents contents = read_vrt(xml);
    if (!contents.refusal.empty()) return contents.refusal;
    sources_ += contents.sources.size();
    if (sources_ > dem_limits::max_sources) return "more than 65536 VRT sources";
    open_vrts_.push_back(path);
    for (const auto& s : contents.sources)
        if (auto e = source(s, path.parent_path(), depth); !e.empty()) {
            open_vrts_.pop_back();
            return "source " + s.name + ": " + e;
        }
    open_vrts_.pop_back();
    return {};
}

std::string Checker::source(const VrtSource& s, const fs::path& vrt_dir, int depth) {
    if (s.name.empty()) return "an empty name";
    // GDAL reads "x:..." as a driver's connection string and "<VRTDataset" as an inline VRT.
    if (s.name.find_first_of(":\\<") != std::string::npos && !starts_with_ci(s.name, "/vsi"))
        return "not a local file path";
    const fs::path name(s.name);
    for (const auto& part : name)
        if (part == "..")
            return "\"..\" in a source's path (put the VRT in its sources' folder or above it)";
    fs::path path;
    if (name.is_absolute())
        path = name;
    else if (s.relative_to_vrt)
        path = vrt_dir / name;
    else
        return "relative to gimbald's working directory (relativeToVRT=\"0\"): name it relative "
               "to the VRT or absolutely";
    if (s.scale_x > dem_limits::max_source_scale || s.scale_y > dem_limits::max_source_scale)
        return "read down-sampled more than 16:1 (SrcRect / DstRect)";
    return file(path.string(), depth + 1);
}

}  // namespace

std::vector<fs::path> dem_folders(const std::vector<std::string>& patterns) {
    std::vector<fs::path> out;
    for (const auto& pattern : patterns) {
        fs::path folder;
        const fs::path p(pattern);
        if (!has_wildcard(pattern)) {
            folder = p.parent_path();
        } else {
            for (const auto& part : p) {
                if (has_wildcard(part.string())) break;
                folder /= part;
            }
        }
        if (folder.empty()) folder = ".";
        std::error_code ec;
        fs::path resolved = fs::canonical(folder, ec);
        if (ec) resolved = fs::absolute(folder, ec).lexically_normal();
        if (std::find(out.begin(), out.end(), resolved) == out.end()) out.push_back(resolved);
    }
    return out;
}

std::string check_dem_name(const std::string& pattern) {
    const auto e = not_local(pattern);
    return e.empty() ? e : pattern + ": " + e;
}

Result<CheckedDem> check_dem_file(const std::string& path, const std::vector<fs::path>& folders) {
    gdal_init();
    Checker checker(folders);
    CheckedDem out;
    if (auto e = checker.file(path, 0, &out); !e.empty())
        return Error{code::unavailable, path + ": " + e};
    return out;
}

std::string check_raster_size(GDALDatasetH ds) {
    const int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
    if (static_cast<double>(w) * static_cast<double>(h) > dem_limits::max_cells)
        return std::to_string(w) + " x " + std::to_string(h) +
               " cells: more than 2^31 (2147483648)";
    for (int b = 1; b <= GDALGetRasterCount(ds); ++b) {
        GDALRasterBandH band = GDALGetRasterBand(ds, b);
        int bx = 0, by = 0;
        GDALGetBlockSize(band, &bx, &by);
        const double bytes = static_cast<double>(bx) * static_cast<double>(by) *
                             GDALGetDataTypeSizeBytes(GDALGetRasterDataType(band));
        if (bytes > static_cast<double>(dem_limits::max_block_bytes))
            return "blocks of " + std::to_string(bx) + " x " + std::to_string(by) +
                   " cells (more than 16 MiB each): write it tiled (gdal_translate -co "
                   "TILED=YES)";
    }
    double gt[6];
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    if (GDALGetGeoTransform(ds, gt) != CE_None || !srs) return {};
    if (!std::all_of(gt, gt + 6, [](double v) { return std::isfinite(v); }))
        return "a geotransform that is not finite";
    double unit = 1;
    if (OSRIsGeographic(srs))
        unit = metres_per_degree;
    else if (const double u = OSRGetLinearUnits(srs, nullptr); u > 0)
        unit = u;
    const double cell_m = std::min(std::hypot(gt[1], gt[4]), std::hypot(gt[2], gt[5])) * unit;
    if (!(cell_m >= dem_limits::min_cell_m))
        return "cells of " + number(cell_m) + " m: smaller than 1 mm";
    return {};
}

}  // namespace gimbal::terrain
