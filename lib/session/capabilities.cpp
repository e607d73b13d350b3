#include "session/capabilities.hpp"

#include <cmath>

namespace gimbal::session {

std::vector<std::string> Capabilities::names() const {
    const Features f = features();
    std::vector<std::string> out;
    if (f.point_angles) out.emplace_back("point_angles");
    if (f.rate) out.emplace_back("rate");
    if (f.geopoint) out.emplace_back("geopoint");
    if (f.zoom) out.emplace_back("zoom");
    return out;
}

const nlohmann::json* state_at(const nlohmann::json& state,
                               std::initializer_list<const char*> keys) {
    const nlohmann::json* at = &state;
    for (const char* k : keys) {
        if (!at->is_object()) return nullptr;
        const auto it = at->find(k);
        if (it == at->end() || it->is_null()) return nullptr;
        at = &*it;
    }
    return at;
}

std::optional<double> number_at(const nlohmann::json& state,
                                std::initializer_list<const char*> keys) {
    const nlohmann::json* v = state_at(state, keys);
    if (!v || !v->is_number()) return std::nullopt;
    const double d = v->get<double>();
    if (!std::isfinite(d)) return std::nullopt;
    return d;
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
