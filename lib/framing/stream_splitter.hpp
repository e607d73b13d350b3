// Splits a received byte stream into the protocol's frames and the junk runs between them,
// exactly as the session's framer splits it: what the flight recorder records as one PDU
// each, so the inbound PDUs of a link, concatenated, are the bytes the gimbal sent. Pure.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace gimbal::framing {

class StreamSplitter {
  public:
    // One piece of the stream: a whole valid frame, or bytes that belong to none.
    using Piece = std::function<void(std::span<const std::uint8_t> bytes, bool is_frame)>;

    virtual ~StreamSplitter() = default;
    virtual void push(std::span<const std::uint8_t> bytes, const Piece& out) = 0;
    // A (re)connect or disconnect: the held partial frame belongs to nothing; it comes out as
    // junk.
    virtual void flush(const Piece& out) = 0;
};

// Runs its own copy of the session's framer over the same bytes. The framer counts every
// byte it discards (dropped_bytes) before it delivers the frame that follows them, and frames
// are contiguous, so the counter's growth at each frame is the junk run just before it.
// SizeOf(frame) is the frame's length on the wire.
template <class Framer, auto SizeOf>
class FramerSplitter final : public StreamSplitter {
  public:
    void push(std::span<const std::uint8_t> bytes, const Piece& out) override {
        held_.insert(held_.end(), bytes.begin(), bytes.end());
        std::size_t at = 0;
        framer_.push(bytes, [&](const auto& frame) {
            at = emit_junk(at, out);
            const std::size_t size = std::min<std::size_t>(SizeOf(frame), held_.size() - at);
            out(std::span(held_).subspan(at, size), true);
            at += size;
        });
        at = emit_junk(at, out);
        // What the framer still holds is an unfinished frame; anything else beyond it would
        // mean the two views disagree - pass it on as junk rather than lose or repeat bytes.
        const std::size_t pending = framer_.pending_bytes();
        if (held_.size() - at > pending) {
            const std::size_t extra = held_.size() - at - pending;
            out(std::span(held_).subspan(at, extra), false);
            at += extra;
        }
        held_.erase(held_.begin(), held_.begin() + static_cast<long>(at));
    }

    void flush(const Piece& out) override {
        framer_.reset();
        dropped_seen_ = framer_.stats().dropped_bytes;
        if (!held_.empty()) out(held_, false);
        held_.clear();
    }

  private:
    std::size_t emit_junk(std::size_t at, const Piece& out) {
        const std::uint64_t dropped = framer_.stats().dropped_bytes;
        auto junk = static_cast<std::size_t>(dropped - dropped_seen_);
        dropped_seen_ = dropped;
        junk = std::min(junk, held_.size() - at);
        if (junk == 0) return at;
        out(std::span(held_).subspan(at, junk), false);
        return at + junk;
    }

    Framer framer_;
    std::uint64_t dropped_seen_ = 0;
    std::vector<std::uint8_t> held_;  // received bytes not passed on yet
};

}  // namespace gimbal::framing
