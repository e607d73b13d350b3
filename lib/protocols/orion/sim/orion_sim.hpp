// A simulated Trillium Orion gimbal behind the byte-level Device interface: what the daemon's
// sim link and the gimbal-sim tool serve. See docs/simulator.md for the behaviour in full.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geo/wgs84.hpp"
#include "protocols/orion/codec/enums.hpp"
#include "sim/device.hpp"

namespace gimbal::sim {

// A pointer and a LightWare rangefinder, the gimbal's usual fit.
std::vector<orion::LaserType> default_lasers();

struct OrionSimOptions {
    // The aircraft flies a level circle around this centre (WGS84, height above the ellipsoid).
    double lat_deg = 45.7;
    double lon_deg = -121.5;
    double alt_m = 1500;
    double radius_m = 1000;
    double speed_mps = 25;  // 0 hovers at the centre
    bool clockwise = true;
    // Where the line of sight meets the ground (its range, the reported target): flat ground
    // at this height above the ellipsoid, or when not set the analytic terrain of
    // sim/terrain.hpp (hills and a valley around the demo area).
    std::optional<double> terrain_alt_m;
    // Reported geoid height above the ellipsoid (MSL altitude = WGS84 altitude - this).
    double geoid_undulation_m = -21;

    // Axes: slew rate limits and tilt end stops (pan turns without end stops).
    double pan_rate_max_dps = 60;
    double tilt_rate_max_dps = 60;
    double tilt_min_deg = -120;
    double tilt_max_deg = 30;

    // Path mode and step-stare.
    double path_scan_speed_mps = 100;
    double stare_time_s = 1.0;  // StareStart maxStareTime, at most 2.55
    double step_timeout_s = 2.0;
    double on_target_deg = 0.5;

    // Lasers by index; an empty password means none is needed. The default list is made out
    // of line: built inline from an initializer list in every caller, GCC 12 -O3 on aarch64
    // reports its constant backing array as maybe uninitialized (a false positive that
    // -Werror makes fatal).
    std::vector<orion::LaserType> lasers = default_lasers();
    std::string laser_password;
    // Once OrionAutopilotData arrives, fire needs Agl at least this (and CommGood, IsFlying).
    double laser_min_agl_m = 30;
    bool retract_installed = true;

    // GPS time (seconds since 1980-01-06, leap seconds included) when the model starts, and
    // the gimbal's uptime then. The model never reads a clock: the caller passes these.
    double gps_time_at_start_s = 1419724818.0;  // 2025-01-01T00:00:00Z
    std::uint32_t uptime_at_start_ms = 0;
    std::uint8_t leap_seconds = 18;

    std::uint32_t seed = 1;  // sensor noise; the same seed gives the same bytes
};

std::unique_ptr<Device> make_orion_sim(const OrionSimOptions& options = {});

// What the simulated Orion's active camera looks at, at the model's current time (that of the
// latest receive or advance): for rendering its video (sim_camera.hpp).
struct OrionCameraView {
    double model_time_s = 0;  // seconds since the model's start
    geo::Lla position;        // the gimbal
    geo::Quat mount_to_ned;   // the mount's attitude, as telemetry's quat
    double pan_rad = 0;       // pan and tilt as telemetry reports them
    double tilt_rad = 0;
    double hfov_rad = 0;  // the active camera's fields of view at its zoom
    double vfov_rad = 0;
    bool infrared = false;  // the active camera is the LWIR one
    // The geoid height the telemetry reports (MSL = WGS84 - this).
    double geoid_undulation_m = 0;
};
// nullopt when `device` is not a simulated Orion made by make_orion_sim.
std::optional<OrionCameraView> orion_sim_camera(const Device& device);

// GPS time for a Unix time: GPS counts from 1980-01-06 and includes the leap seconds UTC
// skips (18 since 2017).
inline double gps_time_from_unix_s(double unix_s, std::uint8_t leap_seconds = 18) {
    return unix_s - 315964800.0 + leap_seconds;
}

// Wire bytes of the CrownVersion packet the simulated gimbal reports: the discovery reply.
std::vector<std::uint8_t> orion_sim_crown_version_frame();

}  // namespace gimbal::sim
