// What lib/video hands out: access units of H.264/H.265 video (Annex B byte stream, as
// MPEG-TS carries it) and KLV metadata units, each with its 90 kHz timestamps. Views are
// valid only during the callback that delivers them; copy into the *Buffer forms to keep.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace gimbal::video {

enum class Codec : std::uint8_t { h264, h265 };

// "h264" / "h265" (contract section 17 `codec`).
constexpr std::string_view to_string(Codec c) {
    return c == Codec::h264 ? "h264" : "h265";
}

// The largest access unit an input hands on (bytes, Annex B); a larger one is dropped and
// counted. Far above a key frame of a gimbal camera (a 4K intra frame at high quality is a
// few MiB), and small enough that relaying one stays a bounded piece of work for the thread
// that also times the laser dead-man (contract section 14 v4).
inline constexpr std::size_t max_access_unit_bytes = 8u << 20;
// The largest synchronous metadata access unit (ST 1402: one KLV set, whose limit is 64 KiB)
// put together from its fragments, and the largest KLV PES (several sets).
inline constexpr std::size_t max_metadata_au_bytes = 64u << 10;
inline constexpr std::size_t max_klv_pes_bytes = 128u << 10;

// 33-bit MPEG system timestamps at 90 kHz.
inline constexpr std::uint64_t pts_modulus = std::uint64_t{1} << 33;
inline constexpr std::uint64_t pts_hz = 90'000;

struct AccessUnit {
    Codec codec = Codec::h264;
    std::optional<std::uint64_t> pts;
    std::optional<std::uint64_t> dts;    // absent when equal to pts
    bool key_frame = false;              // IDR (H.264) or IRAP (H.265)
    std::span<const std::uint8_t> data;  // Annex B: start codes, NAL units
};

// An owned access unit (to queue or to hand across threads).
struct AccessUnitBuffer {
    Codec codec = Codec::h264;
    std::optional<std::uint64_t> pts;
    std::optional<std::uint64_t> dts;
    bool key_frame = false;
    std::vector<std::uint8_t> data;

    AccessUnitBuffer() = default;
    explicit AccessUnitBuffer(const AccessUnit& au)
        : codec(au.codec),
          pts(au.pts),
          dts(au.dts),
          key_frame(au.key_frame),
          data(au.data.begin(), au.data.end()) {}
    AccessUnit view() const { return {codec, pts, dts, key_frame, data}; }
};

// How the KLV reached us (MISB ST 1402): the asynchronous KLVA data stream (stream_type
// 0x06, private_stream_1) or the synchronous metadata stream (stream_type 0x15, metadata AU
// cells).
enum class KlvCarriage : std::uint8_t { async, sync };

constexpr std::string_view to_string(KlvCarriage c) {
    return c == KlvCarriage::async ? "async" : "sync";
}

struct KlvUnit {
    KlvCarriage carriage = KlvCarriage::async;
    std::optional<std::uint64_t> pts;
    std::span<const std::uint8_t> data;  // one or more whole KLV packets (key, BER length, value)
};

}  // namespace gimbal::video
