// A simulated Viewpro gimbal (target GPS-coordinates protocol) behind the byte-level Device
// interface: what the daemon's sim link and `gimbal-sim --protocol viewpro` serve. It takes
// mode, shift and IN1/IN2/IN3 frames, works out where its line of sight meets the ground, and
// sends the selected OUTx frame at 10 Hz while its mode byte enables serial output. See
// docs/simulator.md.
#pragma once

#include <cstdint>
#include <memory>

#include "sim/device.hpp"

namespace gimbal::sim {

struct ViewproSimOptions {
    // The vehicle before the first IN frame arrives (the ICD's OUT1 example location).
    double lat_deg = 6.9428789;
    double lon_deg = 79.8812446;
    double alt_msl_m = 300;
    double yaw_deg = 0;  // heading; roll and pitch start level

    // Flat terrain at this height above mean sea level: where the line of sight ends when no
    // IN3 laser distance is fresh.
    double terrain_alt_msl_m = 0;
    // Geoid height above the ellipsoid; only converts MSL heights for the geometry.
    double geoid_undulation_m = 0;

    // Gimbal encoder angles relative to the vehicle body: positive pitch looks up, positive
    // yaw turns right (yaw 0 is the vehicle's heading, ICD 2.3). Yaw sweeps at yaw_rate_dps.
    double gimbal_roll_deg = 0;
    double gimbal_pitch_deg = -45;
    double gimbal_yaw_deg = 0;
    double gimbal_yaw_rate_dps = 0;
    double angle_noise_deg = 0;  // Gaussian noise on the reported angles, 1 sigma

    bool has_laser = true;  // OUTx carries the slant range as the LRF distance; else 0
    std::uint16_t zoom_position = 0;

    // The gimbal's power-on mode byte: 0x01, target on OSD, no output (ICD example 1.6).
    std::uint8_t mode_byte = 0x01;

    // UTC (Unix seconds) when the model starts: the OUTx time until a vehicle frame sets it.
    // The model never reads a clock.
    double unix_time_at_start_s = 1735689600.0;  // 2025-01-01T00:00:00Z

    std::uint32_t seed = 1;  // angle noise; the same seed gives the same bytes
};

std::unique_ptr<Device> make_viewpro_sim(const ViewproSimOptions& options = {});

}  // namespace gimbal::sim
