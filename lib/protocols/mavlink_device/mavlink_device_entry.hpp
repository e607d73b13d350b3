// The registry entry of MAVLink gimbal devices (contract section 19; Gremsy, STorM32,
// Freefly ...): the session, splitter, feed, export, simulator and capabilities of this
// folder behind the registry's interfaces.
#pragma once

#include "protocols/registry.hpp"

namespace gimbal::protocols {

const Entry& mavlink_device_entry();
Simulator mavlink_device_simulator();

}  // namespace gimbal::protocols
