// Small JSON helpers the track decoders share.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

namespace gimbal::protocols {

// The number at j[key], or nullopt.
inline std::optional<double> number_value(const nlohmann::json& j, const char* key) {
    if (!j.is_object()) return std::nullopt;
    const auto it = j.find(key);
    if (it == j.end() || !it->is_number()) return std::nullopt;
    return it->get<double>();
}

// to[to_key] = from[from_key], when from has it.
inline void copy_value(nlohmann::json& to, const char* to_key, const nlohmann::json& from,
                       const char* from_key) {
    if (from.is_object() && from.contains(from_key)) to[to_key] = from[from_key];
}

}  // namespace gimbal::protocols
