#include "terrain/elevation_model.hpp"

#include <cpl_conv.h>
#include <glob.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "geo/ray_march.hpp"
#include "geo/sampled_surface.hpp"
#include "terrain/gdal_handle.hpp"

namespace gimbal::terrain {

namespace {

using geo::GeoRect;

constexpr double wgs84_a = 6378137.0;
constexpr double wgs84_f = 1 / 298.257223563;
constexpr double wgs84_e2 = wgs84_f * (2 - wgs84_f);
// Higher than any ground (Everest plus the largest geoid height, with room).
constexpr double highest_ground_m = 9100;
constexpr double bound_margin_m = 0.01;

struct Tile {
    std::string path;
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
    GeoRect area;                 // what its pixels cover
};

// A regular lattice of nodes: node (r, c) at lat_o + r * dlat, lon_o + c * dlon.
struct Lattice {
    double lat_o = 0, lon_o = 0;
    double dlat = 0, dlon = 0;  // dlat < 0 for north-up rasters; dlon > 0
    double cell_m = 0;
    std::vector<std::size_t> tiles;  // in file order
    GeoRect reach;                   // every known cell lies inside
    double lon_mid = 0;
    std::size_t first_file = 0;
};

double radius_meridian(double lat_deg) {
    const double s = std::sin(lat_deg * geo::deg2rad);
    const double w = std::sqrt(1 - wgs84_e2 * s * s);
    return wgs84_a * (1 - wgs84_e2) / (w * w * w);
}

double radius_normal(double lat_deg) {
    const double s = std::sin(lat_deg * geo::deg2rad);
    return wgs84_a / std::sqrt(1 - wgs84_e2 * s * s);
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

bool contains(const GeoRect& r, double lat, double lon) {
    return lat >= r.lat_min && lat <= r.lat_max && lon >= r.lon_min && lon <= r.lon_max;
}

bool intersects(const GeoRect& a, const GeoRect& b) {
    return a.lat_min < b.lat_max && b.lat_min < a.lat_max && a.lon_min < b.lon_max &&
           b.lon_min < a.lon_max;
}

GeoRect unite(const GeoRect& a, const GeoRect& b) {
    return {std::min(a.lat_min, b.lat_min), std::max(a.lat_max, b.lat_max),
            std::min(a.lon_min, b.lon_min), std::max(a.lon_max, b.lon_max)};
}

// Shrinks `region` (which holds the point) so it no longer overlaps `avoid` (which does not).
void clip_away(GeoRect& region, double lat, double lon, const GeoRect& avoid) {
    if (!intersects(region, avoid)) return;
    if (lat <= avoid.lat_min)
        region.lat_max = std::min(region.lat_max, avoid.lat_min);
    else if (lat >= avoid.lat_max)
        region.lat_min = std::max(region.lat_min, avoid.lat_max);
    else if (lon <= avoid.lon_min)
        region.lon_max = std::min(region.lon_max, avoid.lon_min);
    else if (lon >= avoid.lon_max)
        region.lon_min = std::max(region.lon_min, avoid.lon_max);
}

void clip_to(GeoRect& region, const GeoRect& keep) {
    region.lat_min = std::max(region.lat_min, keep.lat_min);
    region.lat_max = std::min(region.lat_max, keep.lat_max);
    region.lon_min = std::max(region.lon_min, keep.lon_min);
    region.lon_max = std::min(region.lon_max, keep.lon_max);
}

bool has_wildcard(const std::string& s) {
    return s.find_first_of("*?[") != std::string::npos;
}

std::string expand(const std::vector<std::string>& patterns, std::vector<std::string>& out) {
    for (const auto& pattern : patterns) {
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

}  // namespace

struct ElevationModel::Impl {
    std::vector<std::string> files;
    std::vector<Tile> tiles;
    std::vector<Lattice> lattices;  // in priority order
    std::optional<Geoid> geoid;
    BlockCache cache;
    std::vector<float> scratch;
    // The block used last, while the cache has not loaded another.
    BlockKey memo_key;
    const Block* memo_block = nullptr;
    std::uint64_t memo_generation = 0;

    explicit Impl(std::size_t budget)
        : cache(budget, [this](const BlockKey& k, Block& b) { load(k, b); }) {}

    std::string open_tile(const std::string& path, Tile& t);
    void place(std::size_t tile_index);
    void load(const BlockKey& key, Block& block);
    void load_geographic(const Lattice& lat, const BlockKey& key, Block& block);
    void load_projected(const Lattice& lat, const Tile& t, const BlockKey& key, Block& block);
    double read_value(const Tile& t, float raw) const;

    const Block& block(const BlockKey& key) {
        if (memo_block && memo_key == key && memo_generation == cache.generation())
            return *memo_block;
        const Block& b = cache.get(key);
        memo_key = key;
        memo_block = &b;
        memo_generation = cache.generation();
        return b;
    }

    struct Cell {
        std::int64_t r = 0, c = 0;
        GeoRect rect;
    };
    Cell cell_at(const Lattice& l, double lat, double lon, double north, double east) const {
        const double rf = (lat - l.lat_o) / l.dlat;
        const double cf = (geo::lon_near(lon, l.lon_mid) - l.lon_o) / l.dlon;
        Cell c;
        c.r = geo::cell_index(rf, north / l.dlat);
        c.c = geo::cell_index(cf, east / l.dlon);
        const double la = l.lat_o + static_cast<double>(c.r) * l.dlat;
        const double lo = l.lon_o + static_cast<double>(c.c) * l.dlon;
        c.rect = {std::min(la, la + l.dlat), std::max(la, la + l.dlat), lo, lo + l.dlon};
        return c;
    }

    std::optional<geo::Patch> find(double lat, double lon, double north, double east,
                                   std::size_t* answered);
};

std::string ElevationModel::Impl::open_tile(const std::string& path, Tile& t) {
    t.path = path;
    t.ds.reset(
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    if (!t.ds) return path + ": cannot read: " + QuietErrors::message();
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
        t.area = {std::min(lat_a, lat_b), std::max(lat_a, lat_b), g[0], g[0] + g[1] * t.width};
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
    t.area = {*std::min_element(ys.begin(), ys.end()), *std::max_element(ys.begin(), ys.end()),
              *std::min_element(xs.begin(), xs.end()), *std::max_element(xs.begin(), xs.end())};
    return {};
}

// Joins a raster to the geographic lattice it lies on, or starts a new lattice.
void ElevationModel::Impl::place(std::size_t index) {
    Tile& t = tiles[index];
    const double* g = t.gt;
    if (t.projected) {
        // Its own lattice, as fine as its pixels, over its extent.
        const double lat_mid = (t.area.lat_min + t.area.lat_max) / 2;
        const double unit = [&] {
            OGRSpatialReferenceH srs = GDALGetSpatialRef(t.ds.get());
            const double u = OSRGetLinearUnits(srs, nullptr);
            return u > 0 ? u : 1.0;
        }();
        const double px_m = std::hypot(g[1], g[4]) * unit, py_m = std::hypot(g[2], g[5]) * unit;
        Lattice l;
        l.dlat = -py_m / radius_meridian(lat_mid) * geo::rad2deg;
        l.dlon = px_m / (radius_normal(lat_mid) * std::cos(lat_mid * geo::deg2rad)) * geo::rad2deg;
        l.lat_o = t.area.lat_max;
        l.lon_o = t.area.lon_min;
        l.cell_m = std::sqrt(px_m * py_m);
        l.tiles = {index};
        l.reach = t.area;
        l.lon_mid = (t.area.lon_min + t.area.lon_max) / 2;
        l.first_file = index;
        lattices.push_back(l);
        return;
    }
    const double lat00 = g[3] + g[5] / 2, lon00 = g[0] + g[1] / 2;
    const double lat_end = lat00 + g[5] * (t.height - 1), lon_end = lon00 + g[1] * (t.width - 1);
    const GeoRect hull{std::min(lat00, lat_end), std::max(lat00, lat_end), lon00, lon_end};
    for (auto& l : lattices) {
        if (l.tiles.empty() || tiles[l.tiles.front()].projected) continue;
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
    Lattice l;
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

double ElevationModel::Impl::read_value(const Tile& t, float raw) const {
    if (std::isnan(raw)) return NAN;
    if (t.has_nodata &&
        (raw == static_cast<float>(t.nodata) || static_cast<double>(raw) == t.nodata))
        return NAN;
    return static_cast<double>(raw) * t.scale + t.offset;
}

void ElevationModel::Impl::load(const BlockKey& key, Block& block) {
    const Lattice& l = lattices[key.lattice];
    const Tile& first = tiles[l.tiles.front()];
    if (first.projected)
        load_projected(l, first, key, block);
    else
        load_geographic(l, key, block);
    if (!geoid) return;
    for (int r = 0; r < Block::nodes; ++r)
        for (int c = 0; c < Block::nodes; ++c) {
            float& h = block.height[static_cast<std::size_t>(r * Block::nodes + c)];
            if (std::isnan(h)) continue;
            const double lat = l.lat_o + static_cast<double>(key.row * Block::cells + r) * l.dlat;
            const double lon = l.lon_o + static_cast<double>(key.col * Block::cells + c) * l.dlon;
            h = static_cast<float>(static_cast<double>(h) + geoid->undulation(lat, lon));
        }
}

void ElevationModel::Impl::load_geographic(const Lattice& l, const BlockKey& key, Block& block) {
    const std::int64_t r_first = key.row * Block::cells, c_first = key.col * Block::cells;
    const std::int64_t r_last = r_first + Block::cells, c_last = c_first + Block::cells;
    for (const std::size_t ti : l.tiles) {
        const Tile& t = tiles[ti];
        const std::int64_t r0 = std::max(r_first, t.r0), r1 = std::min(r_last, t.r0 + t.height - 1);
        const std::int64_t c0 = std::max(c_first, t.c0), c1 = std::min(c_last, t.c0 + t.width - 1);
        if (r0 > r1 || c0 > c1) continue;
        const int w = static_cast<int>(c1 - c0 + 1), h = static_cast<int>(r1 - r0 + 1);
        scratch.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
        QuietErrors quiet;
        if (GDALRasterIO(t.band, GF_Read, static_cast<int>(c0 - t.c0), static_cast<int>(r0 - t.r0),
                         w, h, scratch.data(), w, h, GDT_Float32, 0, 0) != CE_None)
            continue;  // an unreadable window stays unknown
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) {
                float& out = block.height[static_cast<std::size_t>(
                    (r0 - r_first + r) * Block::nodes + (c0 - c_first + c))];
                if (!std::isnan(out)) continue;  // an earlier file has this node
                out = static_cast<float>(read_value(
                    t, scratch[static_cast<std::size_t>(r) * static_cast<std::size_t>(w) +
                               static_cast<std::size_t>(c)]));
            }
    }
}

void ElevationModel::Impl::load_projected(const Lattice& l, const Tile& t, const BlockKey& key,
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
    QuietErrors quiet;
    OCTTransformEx(t.to_raster.get(), n, xs.data(), ys.data(), nullptr, ok.data());
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
    if (!(col_min <= col_max)) return;
    const int wc0 = static_cast<int>(col_min), wr0 = static_cast<int>(row_min);
    const int wc1 = std::min(static_cast<int>(col_max) + 1, t.width - 1);
    const int wr1 = std::min(static_cast<int>(row_max) + 1, t.height - 1);
    const int w = wc1 - wc0 + 1, h = wr1 - wr0 + 1;
    scratch.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    if (GDALRasterIO(t.band, GF_Read, wc0, wr0, w, h, scratch.data(), w, h, GDT_Float32, 0, 0) !=
        CE_None)
        return;
    auto px = [&](int r, int c) {
        return read_value(t,
                          scratch[static_cast<std::size_t>(r - wr0) * static_cast<std::size_t>(w) +
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
}

std::optional<geo::Patch> ElevationModel::Impl::find(double lat, double lon, double north,
                                                     double east, std::size_t* answered) {
    if (!std::isfinite(lat) || !std::isfinite(lon)) return std::nullopt;
    lon = geo::wrap_lon(lon);
    for (std::size_t li = 0; li < lattices.size(); ++li) {
        const Lattice& l = lattices[li];
        if (!contains(l.reach, lat, geo::lon_near(lon, l.lon_mid))) continue;
        const Cell cell = cell_at(l, lat, lon, north, east);
        const std::int64_t br = floor_div(cell.r, Block::cells),
                           bc = floor_div(cell.c, Block::cells);
        const Block& b = block({static_cast<std::uint32_t>(li), br, bc});
        const int r = static_cast<int>(cell.r - br * Block::cells);
        const int c = static_cast<int>(cell.c - bc * Block::cells);
        const float h_r_c = b.at(r, c), h_r_c1 = b.at(r, c + 1);
        const float h_r1_c = b.at(r + 1, c), h_r1_c1 = b.at(r + 1, c + 1);
        if (std::isnan(h_r_c) || std::isnan(h_r_c1) || std::isnan(h_r1_c) || std::isnan(h_r1_c1))
            continue;
        geo::Patch p;
        p.region = cell.rect;
        p.dlat = std::abs(l.dlat);
        p.dlon = l.dlon;
        p.lon0 = cell.rect.lon_min;
        p.lat0 = cell.rect.lat_min;
        // Row r is the north edge when rows run south (dlat < 0).
        const bool r_north = l.dlat < 0;
        p.h_nw = r_north ? h_r_c : h_r1_c;
        p.h_ne = r_north ? h_r_c1 : h_r1_c1;
        p.h_sw = r_north ? h_r1_c : h_r_c;
        p.h_se = r_north ? h_r1_c1 : h_r_c1;
        // Where a higher-priority lattice is known the patch does not answer.
        const double pl = geo::lon_near(lon, l.lon_mid);
        for (std::size_t hi = 0; hi < li; ++hi) {
            const Lattice& h = lattices[hi];
            const double hl = geo::lon_near(lon, h.lon_mid);
            if (contains(h.reach, lat, hl)) {
                // Unknown there (else it would have answered): clip to that unknown cell.
                GeoRect keep = cell_at(h, lat, lon, north, east).rect;
                const double shift = pl - hl;
                keep.lon_min += shift;
                keep.lon_max += shift;
                clip_to(p.region, keep);
            } else {
                GeoRect avoid = h.reach;
                const double shift = pl - hl;
                avoid.lon_min += shift;
                avoid.lon_max += shift;
                clip_away(p.region, lat, pl, avoid);
            }
        }
        if (answered) *answered = li;
        return p;
    }
    return std::nullopt;
}

ElevationModel::ElevationModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ElevationModel::~ElevationModel() = default;

OpenedModel ElevationModel::open(const TerrainOptions& options) {
    gdal_init();
    QuietErrors quiet;
    if (options.files.empty()) return {nullptr, "terrain.files names no file"};
    if (options.cache_mb <= 0) return {nullptr, "terrain.cache_mb must be positive"};
    const std::size_t budget = static_cast<std::size_t>(options.cache_mb) << 20;
    auto impl = std::make_unique<Impl>(budget);
    if (const auto e = expand(options.files, impl->files); !e.empty()) return {nullptr, e};
    if (options.geoid == GeoidModel::egm96) {
        std::string grid = options.geoid_grid;
        if (grid.empty()) {
            const auto found = Geoid::find_egm96();
            if (!found)
                return {nullptr,
                        "egm96_15.gtx: EGM96 geoid grid not found on PROJ's search path or in "
                        "/usr/share/proj (install proj-data, or set geoid none)"};
            grid = *found;
        }
        auto g = Geoid::open(grid);
        if (!g.geoid) return {nullptr, g.error};
        impl->geoid = std::move(g.geoid);
    }
    impl->tiles.resize(impl->files.size());
    for (std::size_t i = 0; i < impl->files.size(); ++i) {
        if (auto e = impl->open_tile(impl->files[i], impl->tiles[i]); !e.empty())
            return {nullptr, e};
        impl->place(i);
    }
    std::stable_sort(impl->lattices.begin(), impl->lattices.end(),
                     [](const Lattice& a, const Lattice& b) {
                         // Equal within a part in a thousand: file order decides.
                         if (std::abs(a.cell_m - b.cell_m) > 1e-3 * std::min(a.cell_m, b.cell_m))
                             return a.cell_m < b.cell_m;
                         return a.first_file < b.first_file;
                     });
    // GDAL's own raster block cache (process-wide) sits under ours: keep it small.
    GDALSetCacheMax64(static_cast<GIntBig>(
        std::clamp<std::size_t>(budget / 8, std::size_t{1} << 20, std::size_t{32} << 20)));
    return {std::unique_ptr<ElevationModel>(new ElevationModel(std::move(impl))), {}};
}

std::optional<double> ElevationModel::height(double lat, double lon) {
    const auto p = impl_->find(lat, lon, 0, 0, nullptr);
    if (!p) return std::nullopt;
    return p->at(lat, lon);
}

std::optional<geo::Patch> ElevationModel::patch(double lat, double lon, double north, double east) {
    return impl_->find(lat, lon, north, east, nullptr);
}

std::optional<geo::Bound> ElevationModel::bound(double lat, double lon, double north, double east,
                                                double alt_m) {
    if (!std::isfinite(lat) || !std::isfinite(lon)) return std::nullopt;
    lon = geo::wrap_lon(lon);
    auto& im = *impl_;
    for (std::size_t li = 0; li < im.lattices.size(); ++li) {
        const Lattice& l = im.lattices[li];
        const double pl = geo::lon_near(lon, l.lon_mid);
        if (!contains(l.reach, lat, pl)) continue;
        const auto cell = im.cell_at(l, lat, lon, north, east);
        const std::int64_t br = floor_div(cell.r, Block::cells),
                           bc = floor_div(cell.c, Block::cells);
        const Block& b = im.block({static_cast<std::uint32_t>(li), br, bc});
        auto rect = [&](std::int64_t r0, std::int64_t c0, int cells) {
            const double la = l.lat_o + static_cast<double>(r0) * l.dlat;
            const double lb = la + cells * l.dlat;
            const double lo = l.lon_o + static_cast<double>(c0) * l.dlon;
            return GeoRect{std::min(la, lb), std::max(la, lb), lo, lo + cells * l.dlon};
        };
        std::optional<geo::Bound> out;
        if (b.all_known && alt_m > b.max + bound_margin_m) {
            out = geo::Bound{rect(br * Block::cells, bc * Block::cells, Block::cells), b.max};
        } else {
            const int sr = static_cast<int>(cell.r - br * Block::cells) / Block::sub;
            const int sc = static_cast<int>(cell.c - bc * Block::cells) / Block::sub;
            if (!b.sub_known[sr][sc]) return std::nullopt;
            out = geo::Bound{rect(br * Block::cells + sr * Block::sub,
                                  bc * Block::cells + sc * Block::sub, Block::sub),
                             b.sub_max[sr][sc]};
        }
        // A higher-priority lattice reaching into the region could answer there instead.
        for (std::size_t hi = 0; hi < li; ++hi) {
            GeoRect reach = im.lattices[hi].reach;
            const double shift = pl - geo::lon_near(lon, im.lattices[hi].lon_mid);
            reach.lon_min += shift;
            reach.lon_max += shift;
            if (intersects(reach, out->region)) return std::nullopt;
        }
        return out;
    }
    return std::nullopt;
}

double ElevationModel::max_height() const {
    return highest_ground_m;
}

std::optional<Elevation> ElevationModel::elevation(double lat, double lon) {
    std::size_t li = 0;
    const auto p = impl_->find(lat, lon, 0, 0, &li);
    if (!p) return std::nullopt;
    Elevation e;
    e.alt_m = p->at(lat, lon);
    if (impl_->geoid) e.alt_msl_m = e.alt_m - impl_->geoid->undulation(lat, lon);
    // The file whose pixels cover the point (first in file order); else the lattice's first.
    const Lattice& l = impl_->lattices[li];
    e.source = impl_->tiles[l.tiles.front()].path;
    for (const std::size_t ti : l.tiles) {
        const Tile& t = impl_->tiles[ti];
        if (contains(t.area, lat,
                     geo::lon_near(geo::wrap_lon(lon), (t.area.lon_min + t.area.lon_max) / 2))) {
            e.source = t.path;
            break;
        }
    }
    return e;
}

std::optional<double> ElevationModel::geoid_undulation(double lat, double lon) const {
    if (!impl_->geoid) return std::nullopt;
    return impl_->geoid->undulation(lat, lon);
}

const std::vector<std::string>& ElevationModel::files() const {
    return impl_->files;
}

CacheStats ElevationModel::cache_stats() const {
    return impl_->cache.stats();
}

}  // namespace gimbal::terrain
