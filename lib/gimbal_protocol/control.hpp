// Who controls a gimbal (MAV_CMD_DO_GIMBAL_MANAGER_CONFIGURE, common.xml): a primary and a
// secondary (sysid, compid). While a primary is set, attitude and ROI commands from anyone
// else are DENIED. Pure.
#pragma once

#include <cstdint>
#include <optional>

#include "mavlink/gimbal_messages.hpp"

namespace gimbal::gimbal_protocol {

struct MavId {
    std::uint8_t sysid = 0;
    std::uint8_t compid = 0;
    bool operator==(const MavId&) const = default;
};

class Control {
  public:
    // param1..param4 of the command (primary sysid, compid, secondary sysid, compid), each
    // 0: no one, -1: unchanged, -2: the sender, -3: the sender releases, else an id 1..255.
    // NaN counts as -1 (unchanged). Anything else (fractions, out of range, inf) is DENIED and
    // changes nothing.
    mavlink::MavResult configure(const MavId& sender, float primary_sysid, float primary_compid,
                                 float secondary_sysid, float secondary_compid);

    // May `sender` steer the gimbal now?
    bool allows(const MavId& sender) const;

    const std::optional<MavId>& primary() const { return primary_; }
    const std::optional<MavId>& secondary() const { return secondary_; }

  private:
    std::optional<MavId> primary_;
    std::optional<MavId> secondary_;
};

}  // namespace gimbal::gimbal_protocol
