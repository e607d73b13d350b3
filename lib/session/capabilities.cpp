#include "session/capabilities.hpp"

#include <cmath>

namespace gimbal::session {

std::vector<std::string> feature_names(const Features& f) {
    std::vector<std::string> out;
    if (f.point_angles) out.emplace_back("point_angles");
    if (f.rate) out.emplace_back("rate");
    if (f.geopoint) out.emplace_back("geopoint");
    if (f.zoom) out.emplace_back("zoom");
    return out;
}

double wrap180(double deg) {
    double d = std::fmod(deg + 180.0, 360.0);
    if (d < 0) d += 360.0;
    return d - 180.0;
}

Request unsupported(std::string message) {
    return Request{command::ErrorCode::unsupported, std::move(message)};
}

Request unavailable(std::string message) {
    return Request{command::ErrorCode::unavailable, std::move(message)};
}

}  // namespace gimbal::session
