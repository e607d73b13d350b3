// The access units since the latest key frame: what a decoder that joins the stream now needs
// to decode the newest picture. gimbald keeps one per gimbal with visual tracking, so a track
// started now begins on the picture the operator boxed, not on the next key frame up to a
// key frame interval later (docs/tracking.md "gimbald's side"). Bounded: a group of pictures
// larger than the limits is dropped and the buffer waits for the next key frame. Pure.
#pragma once

#include <cstddef>
#include <vector>

#include "video/codec.hpp"

namespace gimbal::video {

struct GopBufferLimits {
    std::size_t max_bytes = 4 * 1024 * 1024;
    std::size_t max_units = 600;  // 20 s at 30 fps
};

class GopBuffer {
  public:
    explicit GopBuffer(GopBufferLimits limits = {}) : limits_(limits) {}

    // A key frame starts a new group; other units join the current one, if any.
    void add(const AccessUnit& unit);
    void clear();

    // From a key frame to the newest unit, in order; empty while waiting for a key frame.
    const std::vector<AccessUnitBuffer>& units() const { return units_; }
    std::size_t bytes() const { return bytes_; }
    std::size_t overflows() const { return overflows_; }

  private:
    GopBufferLimits limits_;
    std::vector<AccessUnitBuffer> units_;
    std::size_t bytes_ = 0;
    std::size_t overflows_ = 0;
};

}  // namespace gimbal::video
