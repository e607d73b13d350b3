// Orion's registry entry (Trillium OrionPublic protocol): the session, framer, feed, export,
// simulator and capabilities of lib/orion, state/orion_state, command/orion_commands and
// sim/orion_sim behind the registry's interfaces.
#pragma once

#include "protocols/registry.hpp"

namespace gimbal::protocols {

const Entry& orion_entry();
Simulator orion_simulator();

}  // namespace gimbal::protocols
