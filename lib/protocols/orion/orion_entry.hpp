// Orion's registry entry (Trillium OrionPublic protocol): the session, framer, feed, export,
// discovery, simulator and capabilities of its codec (codec/), state (orion_state), planner
// (orion_commands) and simulated gimbal (sim/) behind the registry's interfaces.
#pragma once

#include "protocols/registry.hpp"

namespace gimbal::protocols {

const Entry& orion_entry();
Simulator orion_simulator();
Discovery orion_discovery();

}  // namespace gimbal::protocols
