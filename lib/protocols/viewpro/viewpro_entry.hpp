// Viewpro's registry entry (target GPS-coordinates protocol): the session, framer, feed,
// export, simulator and capabilities of lib/viewpro, state/viewpro_state,
// command/viewpro_commands and sim/viewpro_sim behind the registry's interfaces.
#pragma once

#include "protocols/registry.hpp"

namespace gimbal::protocols {

const Entry& viewpro_entry();
Simulator viewpro_simulator();

}  // namespace gimbal::protocols
