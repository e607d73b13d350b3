// Where a Viewpro gimbal's line of sight ends: the target GPS-coordinates calculation the
// simulated gimbal performs. Pure geometry on top of sim/frames.hpp; degrees and metres MSL.
#pragma once

#include <optional>

namespace gimbal::sim {

struct ViewproPose {  // the vehicle, as the IN frames describe it
    double lat_deg = 0, lon_deg = 0, alt_msl_m = 0;
    double roll_deg = 0, pitch_deg = 0, yaw_deg = 0;  // aerospace Euler angles, body -> NED
};

struct ViewproLook {       // the line of sight relative to the body (gimbal angles plus shifts)
    double pitch_deg = 0;  // up positive
    double yaw_deg = 0;    // right positive
};

struct ViewproTarget {
    double lat_deg = 0, lon_deg = 0, alt_msl_m = 0;
    double range_m = 0;  // slant range from the vehicle
};

// With range_m (a laser distance) the target is that far along the line of sight; without,
// where the line of sight meets flat terrain at terrain_alt_msl_m. nullopt when it never does
// (looking above the horizon, or flying below the terrain).
std::optional<ViewproTarget> locate_viewpro_target(const ViewproPose& pose, const ViewproLook& look,
                                                   double terrain_alt_msl_m,
                                                   double geoid_undulation_m,
                                                   std::optional<double> range_m = std::nullopt);

}  // namespace gimbal::sim
