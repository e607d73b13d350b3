#include "state/ground_json.hpp"

#include "state/telemetry.hpp"

namespace gimbal::state {

nlohmann::json ground_point_json(const geo::GroundPoint& g) {
    return write(g);
}

}  // namespace gimbal::state
