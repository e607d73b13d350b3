// GET /healthz (contract section 11): healthy when every gimbal's link is up and its
// telemetry is not stale; the body names what is wrong either way.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "gimbal_session.hpp"

namespace gimbald::http {

struct Health {
    bool ok = true;
    // {"ok", "version", "gimbals": {NAME: {"connected","stale","ok"}}, "problems": [TEXT]}
    nlohmann::json body;
};

Health check_health(const std::vector<GimbalSession*>& sessions);

}  // namespace gimbald::http
