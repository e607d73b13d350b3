// A gimbal's video as it arrives, for the console's video WebSocket (contract section 18):
// every access unit of the input, unchanged, on the daemon's io_context. daemon/http reads
// video through this alone.
#pragma once

#include <cstdint>
#include <functional>

#include "video/codec.hpp"

namespace gimbald::video {

class VideoTap {
  public:
    using Viewer = std::function<void(const gimbal::video::AccessUnit&)>;

    virtual ~VideoTap() = default;
    // `viewer` gets every access unit from now on (the view is valid during the call only)
    // until remove_viewer(id). A viewer may remove itself or another from inside the call.
    virtual std::uint64_t add_viewer(Viewer viewer) = 0;
    virtual void remove_viewer(std::uint64_t id) = 0;
};

}  // namespace gimbald::video
