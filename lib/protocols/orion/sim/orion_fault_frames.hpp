// The Orion's frames as the fault injector finds them (sim/fault_injector.hpp): the shape its
// simulator hook gives gimbal-sim's fault options.
#pragma once

#include "sim/fault_injector.hpp"

namespace gimbal::sim {

FrameShape orion_frames();  // D0 0D id len data ck ck

}  // namespace gimbal::sim
