// Streaming MAVLink v1/v2 framer with no I/O: push() any chunk of bytes, get every complete,
// CRC-valid message we know, in order. After a false start (a stray magic byte, a corrupted
// length, a bad CRC, an unknown incompat flag) it resumes the scan one byte after that magic,
// so a frame hidden inside the bytes of a false one is still found.
//
// Frames of ids we do not know cannot have their CRC checked (no CRC_EXTRA): such a frame is
// taken as a frame, skipped and counted, only when the byte after it is a magic byte (the next
// frame starts there); otherwise it is a false start. So an unknown frame is skipped once the
// first byte of the next frame has arrived.
//
// A datagram transport (UDP) carries whole frames: push_datagram() parses one datagram on its
// own - a false start at its end (a plausible header, a length reaching past it) is dropped
// with the datagram instead of waiting for, and swallowing, the next one.
//
// Signed frames (incompat flag 0x01): with accept_signed they are delivered with their
// Message::signature (verified against signing_key when one is given; the replay check is the
// caller's, see SigningStreams), without it they are dropped and counted.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "framing/pending_bytes.hpp"

#include "mavlink/framing.hpp"
#include "mavlink/messages.hpp"
#include "mavlink/signing.hpp"

namespace gimbal::mavlink {

struct FramerOptions {
    bool accept_signed = false;
    std::optional<SigningKey> signing_key;
};

struct FramerStats {
    std::uint64_t bytes = 0;            // bytes pushed
    std::uint64_t frames = 0;           // messages delivered
    std::uint64_t frame_bytes = 0;      // bytes of the frames delivered
    std::uint64_t bad_crc = 0;          // candidate frames of known ids whose CRC failed
    std::uint64_t dropped_bytes = 0;    // bytes that belonged to no frame
    std::uint64_t unknown_ids = 0;      // well-formed frames of ids we do not decode, skipped
    std::uint64_t signed_rejected = 0;  // CRC-valid signed frames, skipped (accept_signed off)
    std::uint64_t bad_incompat = 0;     // v2 candidates with an incompat flag we do not know
    std::uint64_t bad_length = 0;       // v1 candidates shorter than their message
    std::uint64_t skipped_bytes = 0;    // bytes of well-formed frames not delivered
    // Every byte pushed is in frame_bytes, skipped_bytes, dropped_bytes or still pending.
};

class Framer {
  public:
    explicit Framer(FramerOptions options = {}) : options_(options) {}

    // Calls on_message(const Message&) for each decoded message in `bytes`, in order.
    template <class F>
    void push(std::span<const std::uint8_t> bytes, F&& on_message) {
        stats_.bytes += bytes.size();
        pending_.feed(bytes, max_frame_size,
                      [&](std::span<const std::uint8_t> data) { return scan(data, on_message); });
    }

    std::vector<Message> push(std::span<const std::uint8_t> bytes) {
        std::vector<Message> messages;
        push(bytes, [&](const Message& m) { messages.push_back(m); });
        return messages;
    }

    // One whole datagram: every frame in it, nothing held for the next one.
    template <class F>
    void push_datagram(std::span<const std::uint8_t> bytes, F&& on_message) {
        stats_.bytes += bytes.size();
        stats_.dropped_bytes += pending_.clear();  // never any after a datagram
        scan(bytes, on_message, true);
    }

    std::vector<Message> push_datagram(std::span<const std::uint8_t> bytes) {
        std::vector<Message> messages;
        push_datagram(bytes, [&](const Message& m) { messages.push_back(m); });
        return messages;
    }

    // Forget a partial frame (after a reconnect the old bytes belong to nothing).
    void reset() { stats_.dropped_bytes += pending_.clear(); }

    const FramerStats& stats() const { return stats_; }
    std::size_t pending_bytes() const { return pending_.size(); }

  private:
    enum class Outcome { need_more, false_start, skipped, delivered };
    struct Step {
        Outcome outcome;
        std::size_t size = 0;  // frame bytes, for skipped and delivered
    };

    // Judges the candidate frame at `frame` (first byte is a magic byte) with `available`
    // bytes in hand. Counts what it finds, except for need_more; fills message_ on delivered.
    // `last` says no more bytes follow (the end of a datagram): a candidate reaching past it
    // is a false start, and an unknown frame ending exactly there is whole.
    Step examine(const std::uint8_t* frame, std::size_t available, bool last);

    static bool is_magic(std::uint8_t b) { return b == magic_v1 || b == magic_v2; }

    // Returns how many leading bytes of `data` are finished with; the rest is an unfinished
    // frame that needs more bytes.
    template <class F>
    std::size_t scan(std::span<const std::uint8_t> data, F& on_message, bool last = false) {
        const std::size_t n = data.size();
        const std::uint8_t* base = data.data();
        std::size_t i = 0;
        while (i < n) {
            if (!is_magic(base[i])) {  // in a clean stream the next frame starts right here
                const std::size_t from = i;
                while (i < n && !is_magic(base[i])) ++i;
                stats_.dropped_bytes += i - from;
                if (i == n) return n;
            }
            const Step step = examine(base + i, n - i, last);
            switch (step.outcome) {
                case Outcome::need_more:
                    return i;
                case Outcome::false_start:
                    ++stats_.dropped_bytes;
                    ++i;  // re-scan from the byte after this false magic
                    break;
                case Outcome::skipped:
                    stats_.skipped_bytes += step.size;
                    i += step.size;
                    break;
                case Outcome::delivered:
                    ++stats_.frames;
                    stats_.frame_bytes += step.size;
                    i += step.size;
                    on_message(static_cast<const Message&>(message_));
                    break;
            }
        }
        return i;
    }

    FramerOptions options_;
    framing::PendingBytes pending_;
    Message message_;
    FramerStats stats_;
};

}  // namespace gimbal::mavlink
