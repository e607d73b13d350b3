// stare_start for a MAVLink gimbal device (contract section 4's event, the fields an Orion's
// StareStart gives that have a meaning here): a `geopoint` with `stare: true` emits it once,
// when the device's reported line of sight first comes within stare_tolerance_deg of the
// point. A device has no step-stare of its own: gimbald watches its attitude reports. Pure.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>

#include "geo/attitude.hpp"
#include "geo/wgs84.hpp"
#include "sim/path_follower.hpp"

namespace gimbal::protocols {

// The simulated Orion's on-target angle (docs/simulator.md), well inside any field of view.
inline constexpr double stare_tolerance_deg = 0.5;

// What the device reported, with the aircraft's position.
struct StareView {
    geo::Lla camera;          // above the ellipsoid
    geo::Quat line_of_sight;  // the camera's attitude relative to NED (x along the sight)
    std::optional<double> pan_deg;
    double tilt_deg = 0;
    std::uint32_t time_boot_ms = 0;  // the attitude report's
};

// The stare_start event's fields when the line of sight is on `point` (above the
// ellipsoid), else nullopt: the StareStart's keys and units (degrees, metres) for the desired
// point, the gimbal's position, attitude and angles, and the slant range; system_time_ms is
// the device's time_boot_ms of the report.
std::optional<nlohmann::json> stare_start(const geo::Lla& point, const StareView& view);

// A `path` with step-stare (sim::PathFollower, the Orion's semantics) began a stare at a
// station: the stare_start fields with the stare's own flags and timings. `view` is the
// device's latest report (nullopt: gimbal_data_valid false, only the desired point).
nlohmann::json path_stare_start(const sim::StareBegin& begun, const std::optional<StareView>& view);

// The angle between the line of sight and the direction to `point` (degrees).
double pointing_error_deg(const geo::Lla& point, const geo::Lla& camera,
                          const geo::Quat& line_of_sight);

}  // namespace gimbal::protocols
