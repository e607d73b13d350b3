// The outgoing packets of one stream link (TCP, serial), in two lanes (contract section 14):
//
// - safety: laser cease-fires. Always accepted while the link is up; written before every
//   other queued packet, though never inside one - a packet whose first bytes are out is
//   finished first, so the gimbal never sees interleaved bytes. When the bounds are reached,
//   the oldest normal packets not yet started are dropped (displaced, counted) to make room.
//   Its owner is told when the last byte was written, or that it was discarded.
// - normal: everything else, in order, refused when the bounds are reached. A normal packet
//   may be displaced by safety traffic, unless it was queued as `kept` (laser commands: losing
//   one would leave the daemon's record of the laser wrong).
//
// A cease-fire never overtakes a laser command queued before it (the fire it ends): kept
// packets not yet started move into the safety lane, in their order, ahead of it.
//
// No I/O: the writer asks next() for the bytes to write and reports written(n).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "link/link.hpp"

namespace gimbald {

class SendQueue {
  public:
    using Bytes = std::vector<std::uint8_t>;
    enum class Kind { normal, kept };

    explicit SendQueue(SendQueueLimits limits) : limits_(limits) {}

    // Queues a normal packet; false (nothing queued) when the bounds would be exceeded.
    bool push(Bytes packet, Kind kind = Kind::normal);
    // Queues a safety packet behind the other safety packets, ahead of every normal one.
    // Never refused; returns how many normal packets were displaced to make room.
    std::size_t push_safety(Bytes packet, Link::WrittenHandler on_written);

    bool empty() const { return safety_.empty() && normal_.empty(); }
    // The unwritten bytes of the packet being written: the half-written one, else the first
    // safety packet, else the first normal one. Empty when nothing is queued.
    std::span<const std::uint8_t> next() const;

    // `n` bytes of next() went out. When that finished a packet: `packet_done`, and for a
    // safety packet `safety` and its handler (for the caller to call with true).
    struct Written {
        bool packet_done = false;
        bool safety = false;               // the packet finished was a safety packet
        Link::WrittenHandler safety_done;  // its handler (may be empty)
    };
    Written written(std::size_t n);

    // Discards everything (a disconnect). Returns the handlers of the safety packets that were
    // not written, for the caller to call with false; the packets count in dropped().
    std::vector<Link::WrittenHandler> clear();

    std::size_t packets() const { return safety_.size() + normal_.size(); }
    std::size_t safety_packets() const { return safety_.size(); }
    std::size_t bytes() const { return bytes_; }
    bool half_written() const { return offset_ > 0; }
    std::uint64_t displaced() const { return displaced_; }  // normal packets dropped for safety
    std::uint64_t dropped() const { return dropped_; }      // discarded by clear()

  private:
    struct Safety {
        Bytes bytes;
        Link::WrittenHandler on_written;
    };
    struct Normal {
        Bytes bytes;
        Kind kind;
    };
    bool fits(std::size_t size) const;
    // The packet next() writes from: the safety lane's front?
    bool current_is_safety() const;
    // Drops the oldest displaceable normal packet not yet started; false when there is none.
    bool displace_one();

    SendQueueLimits limits_;
    std::deque<Safety> safety_;
    std::deque<Normal> normal_;
    std::size_t bytes_ = 0;
    std::size_t offset_ = 0;         // bytes of the current packet already written
    bool offset_in_safety_ = false;  // with offset_ > 0: the half-written packet's lane
    std::uint64_t displaced_ = 0;
    std::uint64_t dropped_ = 0;
};

}  // namespace gimbald
