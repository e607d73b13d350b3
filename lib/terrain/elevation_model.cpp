#include "terrain/elevation_model.hpp"

#include <algorithm>
#include <cmath>

#include "geo/ray_march.hpp"
#include "geo/sampled_surface.hpp"

namespace gimbal::terrain {

namespace {

using geo::GeoRect;

// Higher than any ground (Everest plus the largest geoid height, with room).
constexpr double highest_ground_m = 9100;
constexpr double bound_margin_m = 0.01;

using Lattice = DemLattice;

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

// The files read right away, on the caller's thread (ElevationModel::open()).
class ReadNow final : public BlockSource {
  public:
    explicit ReadNow(std::unique_ptr<DemReader> reader) : reader_(std::move(reader)) {}
    bool fetch(const BlockKey& key, Block& out) override { return reader_->read(key, out); }
    std::unique_ptr<DemReader> release() { return std::move(reader_); }

  private:
    std::unique_ptr<DemReader> reader_;
};

}  // namespace

struct ElevationModel::Impl {
    std::shared_ptr<const DemLayout> layout;
    const std::vector<Lattice>& lattices;
    std::unique_ptr<ReadNow> own;  // until read_elsewhere()
    BlockSource* source;
    BlockCache cache;
    // The block used last, while the cache has not loaded another.
    BlockKey memo_key;
    const Block* memo_block = nullptr;
    std::uint64_t memo_generation = 0;

    Impl(std::unique_ptr<DemReader> reader, std::size_t budget)
        : layout(reader->layout()),
          lattices(layout->lattices),
          own(std::make_unique<ReadNow>(std::move(reader))),
          source(own.get()),
          cache(budget, [this](const BlockKey& k, Block& b) { return source->fetch(k, b); }) {}

    // nullptr while the source has not got the block.
    const Block* block(const BlockKey& key) {
        if (memo_block && memo_key == key && memo_generation == cache.generation())
            return memo_block;
        const Block* b = cache.get(key);
        if (!b) return nullptr;
        memo_key = key;
        memo_block = b;
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
        // A block still loading is unknown for this lookup, whatever the lattices below say.
        const Block* b = block({static_cast<std::uint32_t>(li), br, bc});
        if (!b) return std::nullopt;
        const int r = static_cast<int>(cell.r - br * Block::cells);
        const int c = static_cast<int>(cell.c - bc * Block::cells);
        const float h_r_c = b->at(r, c), h_r_c1 = b->at(r, c + 1);
        const float h_r1_c = b->at(r + 1, c), h_r1_c1 = b->at(r + 1, c + 1);
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

Result<std::unique_ptr<ElevationModel>> ElevationModel::open(const TerrainOptions& options) {
    if (options.cache_mb <= 0) return Error{code::bad_request, "terrain.cache_mb must be positive"};
    auto opened = DemReader::open(options);
    if (!opened) return opened.error();
    const std::size_t budget = static_cast<std::size_t>(options.cache_mb) << 20;
    auto impl = std::make_unique<Impl>(std::move(opened).value(), budget);
    return std::unique_ptr<ElevationModel>(new ElevationModel(std::move(impl)));
}

std::unique_ptr<DemReader> ElevationModel::read_elsewhere(BlockSource& source) {
    impl_->source = &source;
    if (!impl_->own) return nullptr;
    auto reader = impl_->own->release();
    impl_->own.reset();
    return reader;
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
        const Block* block = im.block({static_cast<std::uint32_t>(li), br, bc});
        if (!block) return std::nullopt;
        const Block& b = *block;
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
    const DemLayout& layout = *impl_->layout;
    if (layout.geoid) e.alt_msl_m = e.alt_m - layout.geoid->undulation(lat, lon);
    // The file whose pixels cover the point (first in file order); else the lattice's first.
    const Lattice& l = impl_->lattices[li];
    e.source = layout.tiles[l.tiles.front()].path;
    for (const std::size_t ti : l.tiles) {
        const DemTile& t = layout.tiles[ti];
        if (contains(t.area, lat,
                     geo::lon_near(geo::wrap_lon(lon), (t.area.lon_min + t.area.lon_max) / 2))) {
            e.source = t.path;
            break;
        }
    }
    return e;
}

std::optional<double> ElevationModel::geoid_undulation(double lat, double lon) const {
    if (!impl_->layout->geoid) return std::nullopt;
    return impl_->layout->geoid->undulation(lat, lon);
}

const std::vector<std::string>& ElevationModel::files() const {
    return impl_->layout->files;
}

CacheStats ElevationModel::cache_stats() const {
    return impl_->cache.stats();
}

}  // namespace gimbal::terrain
