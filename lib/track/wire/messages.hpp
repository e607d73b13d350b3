// The messages between gimbald and gimbal-track (docs/tracking.md "Wire protocol"): one
// datagram each on a SOCK_SEQPACKET socket, a two-byte header (protocol version, message type)
// then the message's fields in the order its fields() visit lists them, little-endian. Each
// message is declared once here; the codec (codec.hpp) and the documentation table
// (describe.hpp) are derived from these declarations. Pure: no OpenCV, no I/O, so gimbald and
// gimbal-track both link it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace gimbal::track::wire {

// Raised whenever a message's layout or meaning changes; hello carries it and a peer with
// another version is refused.
inline constexpr std::uint8_t protocol_version = 1;

// Size caps. A datagram larger than max_datagram_bytes is refused whole; an access unit may
// hold at most max_access_unit_bytes (a 4K intra frame at a high bitrate stays below 2 MiB).
inline constexpr std::size_t max_access_unit_bytes = 4u << 20;
inline constexpr std::size_t max_header_bytes = 64;  // header plus every fixed field
inline constexpr std::size_t max_datagram_bytes = max_access_unit_bytes + max_header_bytes;
inline constexpr std::size_t max_text_bytes = 1000;  // error messages, tracker names
inline constexpr std::size_t max_list_items = 16;

enum class MessageType : std::uint8_t {
    hello = 1,  // gimbal-track -> gimbald, first
    start = 2,  // gimbald -> gimbal-track
    au = 3,     // gimbald -> gimbal-track: one access unit of video
    stop = 4,   // gimbald -> gimbal-track
    box = 5,    // gimbal-track -> gimbald: one per decoded frame while a track runs
    ended = 6,  // gimbal-track -> gimbald
    error = 7,  // gimbal-track -> gimbald
};
std::string_view to_string(MessageType type);

// An enumeration on the wire: one byte, the index of its name in names().
enum class TrackerKind : std::uint8_t { csrt, kcf };
enum class Codec : std::uint8_t { h264, h265 };
enum class BoxState : std::uint8_t { tracking, lost };
// Contract section 20's track_end reasons.
enum class EndReason : std::uint8_t { stopped, overridden, timeout, no_video };

inline constexpr std::array<std::string_view, 2> tracker_names{"csrt", "kcf"};
inline constexpr std::array<std::string_view, 2> codec_names{"h264", "h265"};
inline constexpr std::array<std::string_view, 2> box_state_names{"tracking", "lost"};
inline constexpr std::array<std::string_view, 4> end_reason_names{"stopped", "overridden",
                                                                  "timeout", "no_video"};

// The name of an enumerator; "unknown" for a value outside the enumeration.
template <class E, std::size_t N>
std::string_view name_of(E v, const std::array<std::string_view, N>& names) {
    const auto i = static_cast<std::size_t>(v);
    return i < N ? names[i] : std::string_view("unknown");
}
inline std::string_view to_string(TrackerKind v) {
    return name_of(v, tracker_names);
}
inline std::string_view to_string(Codec v) {
    return name_of(v, codec_names);
}
inline std::string_view to_string(BoxState v) {
    return name_of(v, box_state_names);
}
inline std::string_view to_string(EndReason v) {
    return name_of(v, end_reason_names);
}

// Image coordinates of contract section 16: -1..1 across the picture, x right, y down. A box
// may reach outside the picture (a predicted box while lost), up to this far.
inline constexpr double max_coordinate = 4.0;
// Widths gimbal-track scales frames to (contract section 20's `tracking.width`).
inline constexpr int min_width = 64;
inline constexpr int max_width = 3840;
// Times a track is given (seconds).
inline constexpr double max_seconds = 3600;

// gimbal-track's first message: what it speaks and what it can do.
struct Hello {
    static constexpr MessageType type = MessageType::hello;
    std::uint16_t version = protocol_version;
    std::vector<std::string> trackers;  // the trackers it offers, by name
    std::uint32_t max_au_bytes = max_access_unit_bytes;

    template <class V>
    void fields(V& v) {
        v.u16("version", version, "the protocol version (1)");
        v.strings("trackers", trackers, "tracker names it offers (\"csrt\", \"kcf\")");
        v.u32("max_au_bytes", max_au_bytes, "the largest access unit it accepts");
    }
};

// Start tracking the object in `box` on the next decoded frame. A track already running ends
// first (ended, reason stopped).
struct Start {
    static constexpr MessageType type = MessageType::start;
    std::uint32_t id = 0;
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    TrackerKind tracker = TrackerKind::kcf;
    std::uint16_t width = 640;
    float lost_after_s = 1.0f;
    float reacquire_s = 10.0f;

    template <class V>
    void fields(V& v) {
        v.u32("id", id, "the track's id, echoed in box and ended");
        v.f32("x0", x0, -1, 1, "left edge, image coordinates");
        v.f32("y0", y0, -1, 1, "top edge");
        v.f32("x1", x1, -1, 1, "right edge (> x0)");
        v.f32("y1", y1, -1, 1, "bottom edge (> y0)");
        v.enumeration("tracker", tracker, tracker_names, "the tracker to run");
        v.u16("width", width, min_width, max_width, "frames are scaled to this width");
        v.f32("lost_after_s", lost_after_s, 0, max_seconds,
              "no frame for this long: lost (gimbald's side)");
        v.f32("reacquire_s", reacquire_s, 0, max_seconds,
              "lost for this long: ended, reason timeout");
        if constexpr (V::checking) {
            if (!(x1 > x0 && y1 > y0)) v.invalid("box: x1 must exceed x0 and y1 exceed y0");
        }
    }
};

// One access unit as the video pipeline delivers it (Annex B, parameter sets in front of key
// frames), or a piece of one: a datagram on a Unix socket cannot exceed the sender's send
// buffer (212,992 bytes by default on Debian: net.core.wmem_max), so a larger unit goes as
// consecutive pieces with the same pts_90k, key, codec and total_bytes and the offsets 0, n1,
// n1 + n2, ... (AccessUnitAssembler puts them together). `bytes` views the caller's buffer
// when encoding and the datagram when decoding.
struct AccessUnit {
    static constexpr MessageType type = MessageType::au;
    std::int64_t pts_90k = 0;
    bool key = false;
    Codec codec = Codec::h264;
    std::uint32_t total_bytes = 0;
    std::uint32_t offset = 0;
    std::span<const std::uint8_t> bytes;

    template <class V>
    void fields(V& v) {
        v.i64("pts_90k", pts_90k, "presentation time, 90 kHz (echoed in box)");
        v.boolean("key", key, "a key frame (IDR, parameter sets in front)");
        v.enumeration("codec", codec, codec_names, "the stream's codec");
        v.u32("total_bytes", total_bytes, 0, static_cast<double>(max_access_unit_bytes),
              "the whole access unit's size");
        v.u32("offset", offset, 0, static_cast<double>(max_access_unit_bytes),
              "where this piece starts in it");
        v.bytes("bytes", bytes, max_access_unit_bytes,
                "the piece: Annex B bytes (u32 length first)");
        if constexpr (V::checking) {
            if (std::uint64_t{offset} + bytes.size() > total_bytes)
                v.invalid("offset + piece beyond total_bytes");
        }
    }
};

// Stop the track `id` (ended, reason stopped, follows). Another id: ignored.
struct Stop {
    static constexpr MessageType type = MessageType::stop;
    std::uint32_t id = 0;

    template <class V>
    void fields(V& v) {
        v.u32("id", id, "the track to stop");
    }
};

// The object in one decoded frame.
struct Box {
    static constexpr MessageType type = MessageType::box;
    std::uint32_t id = 0;
    std::int64_t pts_90k = 0;
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    float confidence = 0;
    BoxState state = BoxState::tracking;

    template <class V>
    void fields(V& v) {
        v.u32("id", id, "the track");
        v.i64("pts_90k", pts_90k, "the frame's presentation time (its access unit's)");
        v.f32("x0", x0, -max_coordinate, max_coordinate, "left edge, image coordinates");
        v.f32("y0", y0, -max_coordinate, max_coordinate, "top edge");
        v.f32("x1", x1, -max_coordinate, max_coordinate, "right edge");
        v.f32("y1", y1, -max_coordinate, max_coordinate, "bottom edge");
        v.f32("confidence", confidence, 0, 1, "0..1; below the threshold the state is lost");
        v.enumeration("state", state, box_state_names,
                      "tracking, or lost (the box is the predicted one)");
    }
};

// The track is over; no box for it follows.
struct Ended {
    static constexpr MessageType type = MessageType::ended;
    std::uint32_t id = 0;
    EndReason reason = EndReason::stopped;

    template <class V>
    void fields(V& v) {
        v.u32("id", id, "the track");
        v.enumeration("reason", reason, end_reason_names, "why (contract section 20)");
    }
};

// Something gimbald should log (a refused message, a decoder that cannot open).
struct Error {
    static constexpr MessageType type = MessageType::error;
    std::string message;

    template <class V>
    void fields(V& v) {
        v.string("message", message, "what went wrong, for the log");
    }
};

using Message = std::variant<Hello, Start, AccessUnit, Stop, Box, Ended, Error>;

}  // namespace gimbal::track::wire
