// What the opened elevation files are, as the elevation model needs it to find a point's
// cell: the rasters' names and extents, the lattices they form, the geoid. Made once when
// the files are opened (dem_reader.hpp), never changed after: the io thread's model and the
// thread that reads the files may both read it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geo/surface.hpp"
#include "terrain/block_cache.hpp"
#include "terrain/geoid.hpp"

namespace gimbal::terrain {

struct DemTile {
    std::string path;   // as configured (a glob's match)
    geo::GeoRect area;  // what its pixels cover
};

// A regular lattice of nodes: node (r, c) at lat_o + r * dlat, lon_o + c * dlon.
struct DemLattice {
    double lat_o = 0, lon_o = 0;
    double dlat = 0, dlon = 0;  // dlat < 0 for north-up rasters; dlon > 0
    double cell_m = 0;
    std::vector<std::size_t> tiles;  // in file order
    geo::GeoRect reach;              // every known cell lies inside
    double lon_mid = 0;
    std::size_t first_file = 0;
};

// Whether a block of the lattice holds any cell inside its reach.
inline bool block_in_reach(const DemLattice& l, const BlockKey& key) {
    const double la = l.lat_o + static_cast<double>(key.row * Block::cells) * l.dlat;
    const double lb = la + Block::cells * l.dlat;
    const double lo = l.lon_o + static_cast<double>(key.col * Block::cells) * l.dlon;
    const double le = lo + Block::cells * l.dlon;
    return std::max(la, lb) > l.reach.lat_min && std::min(la, lb) < l.reach.lat_max &&
           le > l.reach.lon_min && lo < l.reach.lon_max;
}

struct DemLayout {
    std::vector<std::string> files;    // globs expanded, in order
    std::vector<DemTile> tiles;        // one per file
    std::vector<DemLattice> lattices;  // in priority order
    std::optional<Geoid> geoid;        // EGM96 (nullopt with geoid none)
};

}  // namespace gimbal::terrain
