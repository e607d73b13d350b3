// The `path` command's parameters (contract section 4): read and checked once for every
// protocol that plans it (the Orion's PathCmd, the MAVLink device's steered path), so both
// refuse the same requests with the same errors.
#pragma once

#include <vector>

#include "command/params.hpp"
#include "command/result.hpp"
#include "geo/vec3.hpp"

namespace gimbal::command {

inline constexpr std::size_t max_path_points = 15;

struct PathRequest {
    bool down = false;            // point straight down; no points
    std::vector<geo::Vec3> ecef;  // the points, WGS84 ECEF metres
    double along_step_deg = 0;    // 0: sweep the path
    unsigned cross_steps = 0;
    double cross_ratio = 0;
};

// Reads every parameter (and refuses unknown ones). alt_ref "terrain" is `unavailable`: the
// daemon resolves it against its terrain before a protocol plans the command.
Result<PathRequest> read_path_request(JsonParams& p);

}  // namespace gimbal::command
