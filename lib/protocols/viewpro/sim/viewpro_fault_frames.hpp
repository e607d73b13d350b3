// The Viewpro's output frames as the fault injector finds them (sim/fault_injector.hpp): the
// shape its simulator hook gives gimbal-sim's fault options.
#pragma once

#include "sim/fault_injector.hpp"

namespace gimbal::sim {

FrameShape viewpro_output_frames();  // FE FB/FC/FD ... ck (OUT1..OUT4)

}  // namespace gimbal::sim
