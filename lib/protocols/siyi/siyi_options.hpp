// The settings of one SIYI session: the daemon-wide ones (SessionSettings) and the gimbal's
// own `siyi` object of its configuration.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "geo/surface.hpp"
#include "protocols/siyi/codec/models.hpp"
#include "protocols/siyi/siyi_config.hpp"

namespace gimbal::protocols {

struct SiyiOptions : SiyiConfig {
    double stale_after_s = 1.0;
    geo::Surface* terrain = nullptr;  // telemetry's footprint and ground
    // The EGM96 undulation at a point (SessionSettings::geoid_undulation); empty: none (0).
    std::function<std::optional<double>(double lat_deg, double lon_deg)> geoid;
};

// From the gimbal's configuration object as config.cpp wrote it.
SiyiOptions read_siyi_options(const nlohmann::json& gimbal);

// The configured model; nullopt for `detect`.
std::optional<siyi::Model> configured_model(SiyiModelSetting setting);

}  // namespace gimbal::protocols
