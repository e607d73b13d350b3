// The bytes of an unfinished frame, carried from one push() of a streaming framer to the
// next. Every framer (Orion, Viewpro, MAVLink) scans the caller's buffer in place and copies
// only what straddles two chunks; this is that shared part.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace gimbal::framing {

class PendingBytes {
  public:
    // Feeds `bytes` to scan(std::span<const std::uint8_t>) -> how many leading bytes it is
    // finished with (frames delivered, junk dropped); what remains is an unfinished frame of
    // at most max_frame bytes, kept for the next feed().
    template <class Scan>
    void feed(std::span<const std::uint8_t> bytes, std::size_t max_frame, Scan&& scan) {
        // Complete the held frame with a bounded slice of the new bytes.
        while (!held_.empty() && !bytes.empty()) {
            const std::size_t held = held_.size();
            const std::size_t take = std::min(bytes.size(), 2 * max_frame - held);
            held_.insert(held_.end(), bytes.begin(), bytes.begin() + static_cast<long>(take));
            const std::size_t used = scan(std::span<const std::uint8_t>(held_));
            if (used >= held) {
                // Every held byte is finished with: go on in the caller's buffer (an
                // unfinished frame at the end of the slice is simply scanned again there).
                bytes = bytes.subspan(used - held);
                held_.clear();
                break;
            }
            bytes = bytes.subspan(take);
            held_.erase(held_.begin(), held_.begin() + static_cast<long>(used));
        }
        if (bytes.empty()) return;
        const std::size_t used = scan(bytes);
        held_.assign(bytes.begin() + static_cast<long>(used), bytes.end());
    }

    // Drops the held bytes (after a reconnect they belong to nothing); returns how many.
    std::size_t clear() {
        const std::size_t n = held_.size();
        held_.clear();
        return n;
    }

    std::size_t size() const { return held_.size(); }

  private:
    std::vector<std::uint8_t> held_;
};

}  // namespace gimbal::framing
