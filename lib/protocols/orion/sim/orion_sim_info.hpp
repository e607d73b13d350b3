// The fixed facts of the simulated Orion: board versions, cameras, limits and the
// configuration it starts with. Answers to zero-length requests are built from these.
#pragma once

#include <cstdint>
#include <vector>

#include "protocols/orion/codec/packets.hpp"
#include "sim/pointing.hpp"

namespace gimbal::sim::info {

orion::ClevisVersion clevis_version();
orion::CrownVersion crown_version();
orion::PayloadVersion payload_version();
orion::TrackerVersion tracker_version();
orion::RetractVersion retract_version();
orion::LensCtlVersion lensctl_version();
// One OrionBoard packet per board (clevis, crown, payload).
std::vector<orion::BoardInfo> boards();

// A visible-light zoom camera (index 0) and a long-wave infrared camera (index 1).
orion::Cameras cameras();

orion::Limits limits(const AxisLimits& axes);
// The axis limits a Limits packet sets (pan end stops are not modelled).
AxisLimits axis_limits(const orion::Limits& limits);

orion::NetworkSettings network_settings();
orion::NetworkVideo network_video();
orion::InsOptions ins_options();
orion::UartConfig uart_config(orion::UserDataPort port);

}  // namespace gimbal::sim::info
