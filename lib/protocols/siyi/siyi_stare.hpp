// stare_start for a SIYI camera (contract section 4's event, with the StareStart fields that
// mean something here): a `geopoint` with `stare: true` emits it once, when the camera's
// reported line of sight first comes within stare_tolerance_deg of the point. The camera
// has no stare of its own: gimbald watches its attitude. Pure.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>

#include "geo/attitude.hpp"
#include "geo/wgs84.hpp"

namespace gimbal::protocols {

// The simulated Orion's on-target angle (docs/simulator.md), well inside any field of view.
inline constexpr double siyi_stare_tolerance_deg = 0.5;

// The camera as the event reports it.
struct SiyiStareView {
    geo::Lla camera;          // above the ellipsoid
    geo::Quat line_of_sight;  // camera -> NED, x along the sight
    double pan_deg = 0, tilt_deg = 0;
    std::uint32_t system_time_ms = 0;  // gimbald's clock: the camera's attitude carries none
};

// The angle between the line of sight and the direction to `point` (degrees).
double siyi_pointing_error_deg(const geo::Lla& point, const geo::Lla& camera,
                               const geo::Quat& line_of_sight);

// The stare_start fields when the line of sight is on `point` (above the ellipsoid), else
// nullopt.
std::optional<nlohmann::json> siyi_stare_start(const geo::Lla& point, const SiyiStareView& view);

}  // namespace gimbal::protocols
