// The `geopoint` command's parameters for a gimbal gimbald aims itself (contract sections 19
// and 22: a MAVLink gimbal device, a SIYI camera), read and checked once, so both refuse the
// same requests with the same errors. The Orion's GeopointCmd carries them to the gimbal.
#pragma once

#include <array>
#include <string_view>

#include "command/params.hpp"
#include "command/result.hpp"
#include "geo/wgs84.hpp"

namespace gimbal::command {

struct AimedGeopoint {
    geo::Lla point;                   // above the WGS84 ellipsoid
    std::array<double, 3> vel_ned{};  // m/s: the point moves
    bool stare = false;               // a stare_start event once the gimbal is on it
};

// Reads every parameter (and refuses unknown ones). `closure` changes nothing: such a gimbal
// always slews at its own top rate. A non-zero joystick_range_m is bad_request (there is no
// joystick on its link; `gimbal` names it: "a SIYI camera"); alt_ref "terrain" is
// `unavailable` (the daemon resolves it before a protocol plans the command); "msl" adds
// `geoid_undulation_m`.
Result<AimedGeopoint> read_aimed_geopoint(JsonParams& p, double geoid_undulation_m,
                                          std::string_view gimbal);

}  // namespace gimbal::command
