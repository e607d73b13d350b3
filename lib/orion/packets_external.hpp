// ICD section: see the comment of each packet.
#pragma once

#include "orion/enums.hpp"
#include "orion/fields.hpp"

namespace gimbal::orion {

using ExternalPackets = PacketList<>;

}  // namespace gimbal::orion
