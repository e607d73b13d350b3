// A height function sampled on a regular latitude/longitude lattice and interpolated
// bilinearly between its nodes: exactly the surface a DEM written from the function at that
// lattice has. Used for analytic terrain (the simulator, tests) without a file.
#pragma once

#include <functional>
#include <optional>

#include "geo/surface.hpp"

namespace gimbal::geo {

// Node (i, j) lies at lat0 + i * dlat, lon0 + j * dlon (dlat, dlon > 0, degrees).
struct Lattice {
    double lat0 = 0;
    double lon0 = 0;
    double dlat = 1.0 / 3600;
    double dlon = 1.0 / 3600;
};

class SampledSurface final : public Surface {
  public:
    using HeightFn = std::function<double(double lat_deg, double lon_deg)>;
    // `max_alt_m` must bound the function from above (it lets rays skip the sky). Outside
    // `coverage` (when given) the surface is unknown.
    SampledSurface(HeightFn fn, Lattice lattice, double max_alt_m,
                   std::optional<GeoRect> coverage = std::nullopt,
                   SurfaceKind kind = SurfaceKind::terrain);

    SurfaceKind kind() const override { return kind_; }
    std::optional<double> height(double lat_deg, double lon_deg) override;
    std::optional<Patch> patch(double lat_deg, double lon_deg, double north, double east) override;
    std::optional<Bound> bound(double lat_deg, double lon_deg, double north, double east,
                               double alt_m) override;
    double max_height() const override { return max_alt_m_; }

  private:
    HeightFn fn_;
    Lattice lattice_;
    double max_alt_m_;
    std::optional<GeoRect> coverage_;
    SurfaceKind kind_;
    // The last patch asked for: a march asks for the same cell more than once.
    long last_i_ = 0, last_j_ = 0;
    std::optional<Patch> last_;
};

// The lattice cell index holding x (in cell units); on a node, the cell a step of sign dx
// enters.
long cell_index(double x, double dx);

}  // namespace gimbal::geo
