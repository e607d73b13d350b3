// Access units sent in pieces (messages.hpp, AccessUnit) put back together on the receiving
// side, and cut into pieces on the sending side. Pure.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "track/wire/messages.hpp"

namespace gimbal::track::wire {

// The datagrams of one access unit cut into pieces of at most piece_bytes (the sender's
// send buffer bounds a datagram); one datagram when it fits. Empty when the unit is larger
// than max_access_unit_bytes or piece_bytes is 0.
std::vector<std::vector<std::uint8_t>> encode_access_unit(std::int64_t pts_90k, bool key,
                                                          Codec codec,
                                                          std::span<const std::uint8_t> bytes,
                                                          std::size_t piece_bytes);

class AccessUnitAssembler {
  public:
    struct Unit {
        std::int64_t pts_90k = 0;
        bool key = false;
        Codec codec = Codec::h264;
        std::span<const std::uint8_t> bytes;  // valid until the next add()
    };

    // Adds a piece; returns the whole unit when this piece completes it. A piece that does
    // not continue the unit being put together (another unit's, a gap, an overlap) drops
    // that unit (counted in dropped()), and starts a new one when its offset is 0.
    std::optional<Unit> add(const AccessUnit& piece);

    std::uint64_t dropped() const { return dropped_; }
    bool assembling() const { return active_; }

  private:
    bool continues(const AccessUnit& piece) const;

    std::vector<std::uint8_t> buffer_;
    AccessUnit head_;  // the unit being put together (bytes unused)
    bool active_ = false;
    std::uint64_t dropped_ = 0;
};

}  // namespace gimbal::track::wire
