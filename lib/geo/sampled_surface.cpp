#include "geo/sampled_surface.hpp"

#include <cmath>

#include "geo/ray_march.hpp"

namespace gimbal::geo {

long cell_index(double x, double dx) {
    const double f = std::floor(x);
    // Within a hair of a node: the direction decides.
    if (dx < 0 && x - f < 1e-9) return static_cast<long>(f) - 1;
    if (dx >= 0 && f + 1 - x < 1e-9) return static_cast<long>(f) + 1;
    return static_cast<long>(f);
}

SampledSurface::SampledSurface(HeightFn fn, Lattice lattice, double max_alt_m,
                               std::optional<GeoRect> coverage, SurfaceKind kind)
    : fn_(std::move(fn)),
      lattice_(lattice),
      max_alt_m_(max_alt_m),
      coverage_(coverage),
      kind_(kind) {}

std::optional<double> SampledSurface::height(double lat, double lon) {
    const auto p = patch(lat, lon, 0, 0);
    if (!p) return std::nullopt;
    return p->at(lat, lon);
}

std::optional<Patch> SampledSurface::patch(double lat, double lon, double north, double east) {
    if (!std::isfinite(lat) || !std::isfinite(lon)) return std::nullopt;
    if (coverage_) {
        const double l = lon_near(lon, (coverage_->lon_min + coverage_->lon_max) / 2);
        if (lat < coverage_->lat_min || lat > coverage_->lat_max || l < coverage_->lon_min ||
            l > coverage_->lon_max)
            return std::nullopt;
        lon = l;
    }
    const long i = cell_index((lat - lattice_.lat0) / lattice_.dlat, north);
    const long j = cell_index((lon - lattice_.lon0) / lattice_.dlon, east);
    if (last_ && i == last_i_ && j == last_j_) return last_;
    Patch p;
    p.lat0 = lattice_.lat0 + static_cast<double>(i) * lattice_.dlat;
    p.lon0 = lattice_.lon0 + static_cast<double>(j) * lattice_.dlon;
    p.dlat = lattice_.dlat;
    p.dlon = lattice_.dlon;
    p.region = {p.lat0, p.lat0 + p.dlat, p.lon0, p.lon0 + p.dlon};
    if (coverage_) {
        p.region.lat_min = std::max(p.region.lat_min, coverage_->lat_min);
        p.region.lat_max = std::min(p.region.lat_max, coverage_->lat_max);
        p.region.lon_min = std::max(p.region.lon_min, coverage_->lon_min);
        p.region.lon_max = std::min(p.region.lon_max, coverage_->lon_max);
    }
    p.h_sw = fn_(p.lat0, p.lon0);
    p.h_se = fn_(p.lat0, p.lon0 + p.dlon);
    p.h_nw = fn_(p.lat0 + p.dlat, p.lon0);
    p.h_ne = fn_(p.lat0 + p.dlat, p.lon0 + p.dlon);
    last_i_ = i;
    last_j_ = j;
    last_ = p;
    return p;
}

std::optional<Bound> SampledSurface::bound(double lat, double lon, double, double, double) {
    if (!std::isfinite(lat) || !std::isfinite(lon)) return std::nullopt;
    if (coverage_) {
        const double l = lon_near(lon, (coverage_->lon_min + coverage_->lon_max) / 2);
        if (lat < coverage_->lat_min || lat > coverage_->lat_max || l < coverage_->lon_min ||
            l > coverage_->lon_max)
            return std::nullopt;
        return Bound{*coverage_, max_alt_m_};
    }
    return Bound{{-90, 90, -180, 180}, max_alt_m_};
}

}  // namespace gimbal::geo
