#include "gimbal_protocol/control.hpp"

#include <cmath>

namespace gimbal::gimbal_protocol {

namespace {

using mavlink::MavResult;

// The new value of one control slot, or nullopt-in-optional for "invalid".
struct Slot {
    bool valid = true;
    std::optional<MavId> value;
};

std::optional<int> whole(float v) {
    if (std::isnan(v)) return -1;
    if (!std::isfinite(v) || v != std::trunc(v) || v < -3 || v > 255) return std::nullopt;
    return static_cast<int>(v);
}

Slot apply(const std::optional<MavId>& current, const MavId& sender, float sysid_param,
           float compid_param) {
    const auto sys = whole(sysid_param);
    const auto comp = whole(compid_param);
    if (!sys || !comp) return {false, current};
    switch (*sys) {
        case -1:
            return {true, current};
        case -2:
            return {true, sender};
        case -3:
            return {true, current == sender ? std::nullopt : current};
        case 0:
            return {true, std::nullopt};
        default:
            if (*comp < 0) return {false, current};  // an id needs a real component id
            return {true, MavId{static_cast<std::uint8_t>(*sys), static_cast<std::uint8_t>(*comp)}};
    }
}

}  // namespace

MavResult Control::configure(const MavId& sender, float primary_sysid, float primary_compid,
                             float secondary_sysid, float secondary_compid) {
    const Slot p = apply(primary_, sender, primary_sysid, primary_compid);
    const Slot s = apply(secondary_, sender, secondary_sysid, secondary_compid);
    if (!p.valid || !s.valid) return MavResult::denied;
    primary_ = p.value;
    secondary_ = s.value;
    return MavResult::accepted;
}

bool Control::allows(const MavId& sender) const {
    if (!primary_) return true;
    return sender == *primary_ || (secondary_ && sender == *secondary_);
}

}  // namespace gimbal::gimbal_protocol
