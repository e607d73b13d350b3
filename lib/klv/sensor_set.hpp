// The UAS Datalink Local Set gimbald generates (contract section 17) from what is known
// about one camera at one moment: a SensorFrame in plain units (degrees, metres MSL), each
// item optional, becomes a LocalSet with the section's tags in its order - 2 first, 3, 5, 6,
// 7, 13-21, 23-25, the corners (26-33, or 82-89 when one is beyond the offsets' reach), 40-42,
// 47, 74 (the VMTI set of a visual track, contract section 20), 65 - and the checksum (1)
// last when encoded. An item whose source is unknown is left out (no frame centre: no 23-25
// and no corners; no target: no 40-42; no track: no 74). Pure: the caller gives the time
// stamp.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "klv/local_set.hpp"
#include "klv/vmti.hpp"

namespace gimbal::klv {

struct GroundPoint {
    double lat_deg = 0;
    double lon_deg = 0;
    std::optional<double> alt_msl_m;  // elevation above mean sea level (ST 0601's datum)
};

struct SensorFrame {
    std::uint64_t time_us = 0;  // precision_time_stamp: microseconds since 1970 (UTC)
    std::optional<std::string> mission_id;

    // The platform (aircraft) attitude: heading 0..360 from true north, pitch and roll.
    std::optional<double> platform_heading_deg, platform_pitch_deg, platform_roll_deg;
    // The sensor: position (altitude above mean sea level) and full fields of view.
    std::optional<double> sensor_lat_deg, sensor_lon_deg, sensor_alt_msl_m;
    std::optional<double> hfov_deg, vfov_deg;
    // The line of sight relative to the platform: azimuth clockwise from the nose, elevation
    // up from the platform's horizontal plane, roll about the line of sight.
    std::optional<double> relative_azimuth_deg, relative_elevation_deg, relative_roll_deg;

    std::optional<double> slant_range_m;
    bool slant_range_measured = false;  // by a laser range finder (else calculated)

    std::optional<GroundPoint> frame_center;
    // Image corners on the ground: upper left, upper right, lower right, lower left.
    std::optional<std::array<LatLon, 4>> corners;
    std::optional<GroundPoint> target;  // the target location, when one is known
    std::optional<VmtiSet> vmti;        // the tracked targets (tag 74), when tracking
};

LocalSet sensor_set(const SensorFrame& frame);

// Degrees into [0, 360).
double wrap360(double deg);

}  // namespace gimbal::klv
