// Viewpro's registry entry (target GPS-coordinates protocol): the session, framer, feed,
// export, simulator and capabilities of its codec (codec/), state (viewpro_state), planner
// (viewpro_commands) and simulated gimbal (sim/) behind the registry's interfaces.
#pragma once

#include "protocols/registry.hpp"

namespace gimbal::protocols {

const Entry& viewpro_entry();
Simulator viewpro_simulator();

}  // namespace gimbal::protocols
