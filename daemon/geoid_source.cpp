#include "geoid_source.hpp"

#include <memory>

namespace gimbald {

using gimbal::terrain::Geoid;

OpenedGeoid open_geoid(const gimbal::terrain::ElevationModel* terrain) {
    OpenedGeoid out;
    // The terrain model's geoid (null with "geoid": "none": then the grid of our own).
    if (terrain && terrain->geoid_undulation(0, 0)) {
        out.undulation = [terrain](double lat, double lon) {
            return terrain->geoid_undulation(lat, lon);
        };
        out.source = "terrain";
        return out;
    }
    const auto path = Geoid::find_egm96();
    if (!path) {
        out.problem =
            "no EGM96 grid (egm96_15.gtx, Debian's proj-data) on PROJ's search path "
            "or in /usr/share/proj";
        return out;
    }
    auto opened = Geoid::open(*path);
    if (!opened) {
        out.problem = opened.error().message;
        return out;
    }
    const auto geoid = std::make_shared<const Geoid>(std::move(opened).value());
    out.undulation = [geoid](double lat, double lon) -> std::optional<double> {
        return geoid->undulation(lat, lon);
    };
    out.source = geoid->path();
    return out;
}

}  // namespace gimbald
