#include "command/geopoint_request.hpp"

#include <string>

namespace gimbal::command {

Result<AimedGeopoint> read_aimed_geopoint(JsonParams& p, double geoid_undulation_m,
                                          std::string_view gimbal) {
    const auto lat = p.number("lat", true);
    const auto lon = p.number("lon", true);
    const auto alt = p.number("alt", true);
    const auto ref = p.choice("alt_ref", false).value_or("wgs84");
    const auto vel = p.numbers("vel_ned", false);
    const auto joystick_range = p.integer_or("joystick_range_m", 0);
    const bool stare = p.boolean_or("stare", false);
    (void)p.boolean_or("closure", false);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (joystick_range != 0)
        return Error{code::bad_request, "joystick_range_m must be 0 for " + std::string(gimbal) +
                                            ": there is no joystick on its link"};
    if (ref == "terrain")
        return Error{code::unavailable, "alt_ref 'terrain' needs gimbald's terrain section"};
    AimedGeopoint g;
    g.point = {*lat, *lon, ref == "msl" ? *alt + geoid_undulation_m : *alt};
    if (vel) g.vel_ned = {(*vel)[0], (*vel)[1], (*vel)[2]};
    g.stare = stare;
    return g;
}

}  // namespace gimbal::command
