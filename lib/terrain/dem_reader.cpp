#include "terrain/dem_reader.hpp"

#include <cpl_conv.h>
#include <glob.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "geo/ray_march.hpp"
#include "terrain/dem_policy.hpp"
#include "terrain/gdal_handle.hpp"

namespace gimbal::terrain {

namespace {

using geo::GeoRect;

constexpr double wgs84_a = 6378137.0;
constexpr double wgs84_f = 1 / 298.257223563;
constexpr double wgs84_e2 = wgs84_f * (2 - wgs84_f);

double radius_meridian(double lat_deg) {
    const double s = std::sin(lat_deg * geo::deg2rad);
    const double w = std::sqrt(1 - wgs84_e2 * s * s);
    return wgs84_a * (1 - wgs84_e2) / (w * w * w);
}

double radius_normal(double lat_deg) {
    const double s = std::sin(lat_deg * geo::deg2rad);
    return wgs84_a / std::sqrt(1 - wgs84_e2 * s * s);
}

GeoRect unite(const GeoRect& a, const GeoRect& b) {
    return {std::min(a.lat_min, b.lat_min), std::max(a.lat_max, b.lat_max),
            std::min(a.lon_min, b.lon_min), std::max(a.lon_max, b.lon_max)};
}

bool has_wildcard(const std::string& s) {
    return s.find_first_of("*?[") != std::string::npos;
}

// Paths and globs to file names (which exist, or the problem naming the pattern).
std::string expand(const std::vector<std::string>& patterns, std::vector<std::string>& out) {
    for (const auto& pattern : patterns) {
        if (auto e = check_dem_name(pattern); !e.empty()) return e;
        if (!has_wildcard(pattern)) {
            std::error_code ec;
            if (!std::filesystem::exists(pattern, ec)) return pattern + ": no such file";
            out.push_back(pattern);
            continue;
        }
        glob_t g{};
        const int rc = glob(pattern.c_str(), 0, nullptr, &g);
        if (rc != 0) {
            globfree(&g);
            return pattern + ": no file matches";
        }
        for (std::size_t i = 0; i < g.gl_pathc; ++i) out.emplace_back(g.gl_pathv[i]);
        globfree(&g);
    }
    // A file named twice (a path and a glob) is read once, at its first place.
    std::vector<std::string> unique;
    for (auto& f : out)
        if (std::find(unique.begin(), unique.end(), f) == unique.end()) unique.push_back(f);
    out = std::move(unique);
    return {};
}

int CPL_STDCALL keep_reading(double, const char*, void* keep_going) {
    const auto* f = static_cast<const std::function<bool()>*>(keep_going);
    return !f || !*f || (*f)() ? TRUE : FALSE;
}

}  // namespace

struct DemReader::Tile {
    Dataset ds;
    GDALRasterBandH band = nullptr;
    int width = 0, height = 0;
    double gt[6]{};
    double inv[6]{};  // georeferenced x, y -> pixel column, row (projected rasters)
    bool projected = false;
    Transform to_raster;  // WGS84 lon/lat -> the raster's CRS (projected rasters)
    bool has_nodata = false;
    double nodata = 0, scale = 1, offset = 0;
    std::int64_t r0 = 0, c0 = 0;  // lattice node of pixel (0, 0) (geographic rasters)
};

DemReader::DemReader() : layout_(std::make_shared<DemLayout>()) {}
DemReader::~DemReader() = default;

std::string DemReader::open_tile(const std::string& path, const std::string& resolved,
                                 const std::string& driver, Tile& t) {
    GeoRect& area = layout_->tiles.back().area;
    const char* const allowed[] = {driver.c_str(), nullptr};
    t.ds.reset(
        GDALOpenEx(resolved.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, allowed, nullptr, nullptr));
    if (!t.ds) return path + ": cannot read: " + QuietErrors::message();
    if (auto e = check_raster_size(t.ds.get()); !e.empty()) return path + ": " + e;
    if (GDALGetRasterCount(t.ds.get()) < 1) return path + ": has no raster band";
    t.width = GDALGetRasterXSize(t.ds.get());
    t.height = GDALGetRasterYSize(t.ds.get());
    if (t.width < 2 || t.height < 2) return path + ": raster smaller than 2 x 2";
    if (GDALGetGeoTransform(t.ds.get(), t.gt) != CE_None)
        return path + ": no georeferencing (geotransform)";
    OGRSpatialReferenceH srs = GDALGetSpatialRef(t.ds.get());
    if (!srs) return path + ": no coordinate reference system";
    t.band = GDALGetRasterBand(t.ds.get(), 1);
    int ok = 0;
    t.nodata = GDALGetRasterNoDataValue(t.band, &ok);
    t.has_nodata = ok != 0;
    t.scale = GDALGetRasterScale(t.band, &ok);
    if (!ok || t.scale == 0) t.scale = 1;
    t.offset = GDALGetRasterOffset(t.band, &ok);
    if (!ok) t.offset = 0;
    const double* g = t.gt;
    if (OSRIsGeographic(srs)) {
        if (g[2] != 0 || g[4] != 0 || !(g[1] > 0) || g[5] == 0)
            return path + ": rotated or east-west flipped geotransform (gdalwarp it north-up)";
        const double lat_a = g[3], lat_b = g[3] + g[5] * t.height;
        area = {std::min(lat_a, lat_b), std::max(lat_a, lat_b), g[0], g[0] + g[1] * t.width};
        return {};
    }
    if (!OSRIsProjected(srs)) return path + ": CRS is neither geographic nor projected";
    t.projected = true;
    if (!GDALInvGeoTransform(t.gt, t.inv)) return path + ": geotransform cannot be inverted";
    SpatialRef raster(OSRClone(srs));
    OSRSetAxisMappingStrategy(raster.get(), OAMS_TRADITIONAL_GIS_ORDER);
    SpatialRef wgs84 = wgs84_lonlat();
    t.to_raster.reset(OCTNewCoordinateTransformation(wgs84.get(), raster.get()));
    Transform to_wgs84(OCTNewCoordinateTransformation(raster.get(), wgs84.get()));
    if (!t.to_raster || !to_wgs84)
        return path + ": cannot transform between WGS84 and its CRS: " + QuietErrors::message();
    // Its extent in lat/lon: points along the raster's edges.
    std::vector<double> xs, ys;
    constexpr int steps = 16;
    for (int i = 0; i <= steps; ++i) {
        const double f = static_cast<double>(i) / steps;
        for (const auto& [px, py] :
             {std::pair{f * t.width, 0.0}, std::pair{f * t.width, 1.0 * t.height},
              std::pair{0.0, f * t.height}, std::pair{1.0 * t.width, f * t.height}}) {
            xs.push_back(g[0] + px * g[1] + py * g[2]);
            ys.push_back(g[3] + px * g[4] + py * g[5]);
        }
    }
    std::vector<int> success(xs.size());
    if (!OCTTransformEx(to_wgs84.get(), static_cast<int>(xs.size()), xs.data(), ys.data(), nullptr,
                        success.data()) ||
        std::find(success.begin(), success.end(), 0) != success.end())
        return path + ": cannot transform its extent to WGS84";
    area = {*std::min_element(ys.begin(), ys.end()), *std::max_element(ys.begin(), ys.end()),
            *std::min_element(xs.begin(), xs.end()), *std::max_element(xs.begin(), xs.end())};
    return {};
}

// Joins a raster to the geographic lattice it lies on, or starts a new lattice.
void DemReader::place(std::size_t index) {
    Tile& t = tiles_[index];
    const GeoRect& area = layout_->tiles[index].area;
    auto& lattices = layout_->lattices;
    const double* g = t.gt;
    if (t.projected) {
        // Its own lattice, as fine as its pixels, over its extent.
        const double lat_mid = (area.lat_min + area.lat_max) / 2;
        const double unit = [&] {
            OGRSpatialReferenceH srs = GDALGetSpatialRef(t.ds.get());
            const double u = OSRGetLinearUnits(srs, nullptr);
            return u > 0 ? u : 1.0;
        }();
        const double px_m = std::hypot(g[1], g[4]) * unit, py_m = std::hypot(g[2], g[5]) * unit;
        DemLattice l;
        l.dlat = -py_m / radius_meridian(lat_mid) * geo::rad2deg;
        l.dlon = px_m / (radius_normal(lat_mid) * std::cos(lat_mid * geo::deg2rad)) * geo::rad2deg;
        l.lat_o = area.lat_max;
        l.lon_o = area.lon_min;
        l.cell_m = std::sqrt(px_m * py_m);
        l.tiles = {index};
        l.reach = area;
        l.lon_mid = (area.lon_min + area.lon_max) / 2;
        l.first_file = index;
        lattices.push_back(l);
        return;
    }
    const double lat00 = g[3] + g[5] / 2, lon00 = g[0] + g[1] / 2;
    const double lat_end = lat00 + g[5] * (t.height - 1), lon_end = lon00 + g[1] * (t.width - 1);
    const GeoRect hull{std::min(lat00, lat_end), std::max(lat00, lat_end), lon00, lon_end};
    for (auto& l : lattices) {
        if (l.tiles.empty() || tiles_[l.tiles.front()].projected) continue;
        if (std::abs(g[1] - l.dlon) > 1e-9 * g[1] ||
            std::abs(g[5] - l.dlat) > 1e-9 * std::abs(g[5]))
            continue;
        const double ro = (lat00 - l.lat_o) / l.dlat;
        const double co = (geo::lon_near(lon00, l.lon_o) - l.lon_o) / l.dlon;
        if (std::abs(ro - std::round(ro)) > 1e-3 || std::abs(co - std::round(co)) > 1e-3) continue;
        t.r0 = static_cast<std::int64_t>(std::llround(ro));
        t.c0 = static_cast<std::int64_t>(std::llround(co));
        l.tiles.push_back(index);
        const double shift = geo::lon_near(lon00, l.lon_o) - lon00;
        l.reach = unite(l.reach,
                        {hull.lat_min, hull.lat_max, hull.lon_min + shift, hull.lon_max + shift});
        l.lon_mid = (l.reach.lon_min + l.reach.lon_max) / 2;
        return;
    }
    DemLattice l;
    l.lat_o = lat00;
    l.lon_o = lon00;
    l.dlat = g[5];
    l.dlon = g[1];
    const double lat_mid = (hull.lat_min + hull.lat_max) / 2;
    l.cell_m = std::sqrt(std::abs(g[5]) * geo::deg2rad * radius_meridian(lat_mid) * g[1] *
                         geo::deg2rad * radius_normal(lat_mid) * std::cos(lat_mid * geo::deg2rad));
    l.tiles = {index};
    l.reach = hull;
    l.lon_mid = (hull.lon_min + hull.lon_max) / 2;
    l.first_file = index;
    lattices.push_back(l);
}

double DemReader::read_value(const Tile& t, float raw) const {
    if (std::isnan(raw)) return NAN;
    if (t.has_nodata &&
        (raw == static_cast<float>(t.nodata) || static_cast<double>(raw) == t.nodata))
        return NAN;
    return static_cast<double>(raw) * t.scale + t.offset;
}

// GDAL reads a window of band 1 into scratch_ as Float32, asking keep_going_ as it goes.
bool DemReader::read_window(const Tile& t, int x, int y, int w, int h) {
    scratch_.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    GDALRasterIOExtraArg extra;
    INIT_RASTERIO_EXTRA_ARG(extra);
    extra.pfnProgress = keep_reading;
    extra.pProgressData = const_cast<std::function<bool()>*>(keep_going_);
    QuietErrors quiet;
    return GDALRasterIOEx(t.band, GF_Read, x, y, w, h, scratch_.data(), w, h, GDT_Float32, 0, 0,
                          &extra) == CE_None;
}

bool DemReader::read(const BlockKey& key, Block& block, const std::function<bool()>& keep_going) {
    keep_going_ = &keep_going;
    block.height.assign(static_cast<std::size_t>(Block::nodes * Block::nodes), NAN);
    const DemLattice& l = layout_->lattices[key.lattice];
    const Tile& first = tiles_[l.tiles.front()];
    const bool complete =
        first.projected ? load_projected(l, first, key, block) : load_geographic(l, key, block);
    keep_going_ = nullptr;
    if (!complete) return false;
    if (layout_->geoid)
        for (int r = 0; r < Block::nodes; ++r)
            for (int c = 0; c < Block::nodes; ++c) {
                float& h = block.height[static_cast<std::size_t>(r * Block::nodes + c)];
                if (std::isnan(h)) continue;
                const double lat =
                    l.lat_o + static_cast<double>(key.row * Block::cells + r) * l.dlat;
                const double lon =
                    l.lon_o + static_cast<double>(key.col * Block::cells + c) * l.dlon;
                h = static_cast<float>(static_cast<double>(h) +
                                       layout_->geoid->undulation(lat, lon));
            }
    block.summarise();
    return true;
}

bool DemReader::load_geographic(const DemLattice& l, const BlockKey& key, Block& block) {
    const std::int64_t r_first = key.row * Block::cells, c_first = key.col * Block::cells;
    const std::int64_t r_last = r_first + Block::cells, c_last = c_first + Block::cells;
    for (const std::size_t ti : l.tiles) {
        const Tile& t = tiles_[ti];
        const std::int64_t r0 = std::max(r_first, t.r0), r1 = std::min(r_last, t.r0 + t.height - 1);
        const std::int64_t c0 = std::max(c_first, t.c0), c1 = std::min(c_last, t.c0 + t.width - 1);
        if (r0 > r1 || c0 > c1) continue;
        const int w = static_cast<int>(c1 - c0 + 1), h = static_cast<int>(r1 - r0 + 1);
        if (!read_window(t, static_cast<int>(c0 - t.c0), static_cast<int>(r0 - t.r0), w, h)) {
            if (keep_going_ && *keep_going_ && !(*keep_going_)()) return false;
            continue;  // an unreadable window stays unknown
        }
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) {
                float& out = block.height[static_cast<std::size_t>(
                    (r0 - r_first + r) * Block::nodes + (c0 - c_first + c))];
                if (!std::isnan(out)) continue;  // an earlier file has this node
                out = static_cast<float>(read_value(
                    t, scratch_[static_cast<std::size_t>(r) * static_cast<std::size_t>(w) +
                                static_cast<std::size_t>(c)]));
            }
    }
    return true;
}

bool DemReader::load_projected(const DemLattice& l, const Tile& t, const BlockKey& key,
                               Block& block) {
    constexpr int n = Block::nodes * Block::nodes;
    std::vector<double> xs(n), ys(n);
    std::vector<int> ok(n);
    for (int r = 0; r < Block::nodes; ++r)
        for (int c = 0; c < Block::nodes; ++c) {
            const auto i = static_cast<std::size_t>(r * Block::nodes + c);
            ys[i] = l.lat_o + static_cast<double>(key.row * Block::cells + r) * l.dlat;
            xs[i] = l.lon_o + static_cast<double>(key.col * Block::cells + c) * l.dlon;
        }
    {
        QuietErrors quiet;
        OCTTransformEx(t.to_raster.get(), n, xs.data(), ys.data(), nullptr, ok.data());
    }
    // Pixel-centre coordinates of every node, and the window that holds them.
    double col_min = INFINITY, col_max = -INFINITY, row_min = INFINITY, row_max = -INFINITY;
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
        if (!ok[i]) continue;
        const double x = xs[i], y = ys[i];
        xs[i] = t.inv[0] + t.inv[1] * x + t.inv[2] * y - 0.5;
        ys[i] = t.inv[3] + t.inv[4] * x + t.inv[5] * y - 0.5;
        if (xs[i] < 0 || ys[i] < 0 || xs[i] > t.width - 1 || ys[i] > t.height - 1) {
            ok[i] = 0;
            continue;
        }
        col_min = std::min(col_min, xs[i]);
        col_max = std::max(col_max, xs[i]);
        row_min = std::min(row_min, ys[i]);
        row_max = std::max(row_max, ys[i]);
    }
    if (!(col_min <= col_max)) return true;
    const int wc0 = static_cast<int>(col_min), wr0 = static_cast<int>(row_min);
    const int wc1 = std::min(static_cast<int>(col_max) + 1, t.width - 1);
    const int wr1 = std::min(static_cast<int>(row_max) + 1, t.height - 1);
    const int w = wc1 - wc0 + 1, h = wr1 - wr0 + 1;
    if (!read_window(t, wc0, wr0, w, h)) return !(keep_going_ && *keep_going_ && !(*keep_going_)());
    auto px = [&](int r, int c) {
        return read_value(t,
                          scratch_[static_cast<std::size_t>(r - wr0) * static_cast<std::size_t>(w) +
                                   static_cast<std::size_t>(c - wc0)]);
    };
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
        if (!ok[i]) continue;
        const int c = std::min(static_cast<int>(xs[i]), t.width - 2);
        const int r = std::min(static_cast<int>(ys[i]), t.height - 2);
        const double fx = xs[i] - c, fy = ys[i] - r;
        const double v = (1 - fy) * ((1 - fx) * px(r, c) + fx * px(r, c + 1)) +
                         fy * ((1 - fx) * px(r + 1, c) + fx * px(r + 1, c + 1));
        block.height[i] = static_cast<float>(v);  // NaN when a pixel is nodata
    }
    return true;
}

namespace {
Error unusable(std::string message) {
    return {code::unavailable, std::move(message)};
}
}  // namespace

Result<std::unique_ptr<DemReader>> DemReader::open(const TerrainOptions& options) {
    gdal_init();
    QuietErrors quiet;
    if (options.files.empty()) return unusable("terrain.files names no file");
    std::unique_ptr<DemReader> reader(new DemReader());
    DemLayout& layout = *reader->layout_;
    if (const auto e = expand(options.files, layout.files); !e.empty()) return unusable(e);
    if (options.geoid == GeoidModel::egm96) {
        std::string grid = options.geoid_grid;
        if (grid.empty()) {
            const auto found = Geoid::find_egm96();
            if (!found)
                return unusable(
                    "egm96_15.gtx: EGM96 geoid grid not found on PROJ's search path or in "
                    "/usr/share/proj (install proj-data, or set geoid none)");
            grid = *found;
        }
        auto g = Geoid::open(grid);
        if (!g) return g.error();
        layout.geoid = std::move(g).value();
    }
    const auto folders = dem_folders(options.files);
    reader->tiles_.resize(layout.files.size());
    for (std::size_t i = 0; i < layout.files.size(); ++i) {
        const std::string& path = layout.files[i];
        const auto checked = check_dem_file(path, folders);
        if (!checked) return checked.error();
        layout.tiles.push_back({path, {}});
        if (auto e = reader->open_tile(path, checked->path, checked->driver, reader->tiles_[i]);
            !e.empty())
            return unusable(e);
        reader->place(i);
    }
    std::stable_sort(layout.lattices.begin(), layout.lattices.end(),
                     [](const DemLattice& a, const DemLattice& b) {
                         // Equal within a part in a thousand: file order decides.
                         if (std::abs(a.cell_m - b.cell_m) > 1e-3 * std::min(a.cell_m, b.cell_m))
                             return a.cell_m < b.cell_m;
                         return a.first_file < b.first_file;
                     });
    // GDAL's own raster block cache (process-wide) sits under ours: keep it small.
    const std::size_t budget = static_cast<std::size_t>(std::max(options.cache_mb, 1)) << 20;
    GDALSetCacheMax64(static_cast<GIntBig>(
        std::clamp<std::size_t>(budget / 8, std::size_t{1} << 20, std::size_t{32} << 20)));
    return reader;
}

}  // namespace gimbal::terrain
