// The registry entry of SIYI gimbal cameras (docs/siyi.md; A8 mini, ZR10, ZR30, ZT30, ZT6):
// the session, splitter, feed, export, simulator and capabilities of this folder behind the
// registry's interfaces.
#pragma once

#include "protocols/registry.hpp"

namespace gimbal::protocols {

const Entry& siyi_entry();
Simulator siyi_simulator();

}  // namespace gimbal::protocols
