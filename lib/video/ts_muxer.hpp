// MPEG-TS multiplexer for one program: the video access units copied into PES packets with
// their own PTS/DTS, and one asynchronous KLV data stream as MISB ST 1402 describes it
// (stream_type 0x06, registration descriptor 'KLVA', PES stream_id 0xBD private_stream_1).
//
// - PAT and PMT before the first unit, before every key frame and whenever psi_interval of
//   stream time has passed since the last ones (players can join at any time).
// - PCR on the video PID in the first packet of every access unit (one frame apart),
//   PCR = DTS - pcr_lead, never going back; when KLV arrives and no PCR went out for
//   pcr_interval, a PCR-only packet keeps the clock going (slow or stalled video).
// - Continuity counters per PID, adaptation-field stuffing, random_access_indicator on key
//   frames.
// - Output in chunks of packets_per_chunk packets (7 x 188 = 1316 bytes: one UDP datagram);
//   after each unit the partial chunk is handed out too, so nothing waits for the next frame.
// Pure: time is the stream's 90 kHz timestamps; the sink gets views valid during the call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "video/codec.hpp"

namespace gimbal::video {

struct MuxerOptions {
    std::uint16_t transport_stream_id = 1;
    std::uint16_t program_number = 1;
    std::uint16_t pmt_pid = 0x1000;
    std::uint16_t video_pid = 0x0100;
    std::uint16_t klv_pid = 0x0101;
    bool klv = true;                           // declare the KLV data stream in the PMT
    std::uint64_t psi_interval = pts_hz / 4;   // 250 ms, in 90 kHz ticks
    std::uint64_t pcr_interval = pts_hz / 11;  // ~90 ms: KLV-only PCRs when video stalls
    std::uint64_t pcr_lead = pts_hz / 10;      // PCR this far behind the DTS (decoder buffer)
    std::size_t packets_per_chunk = 7;
};

struct MuxStats {
    std::uint64_t packets = 0;
    std::uint64_t chunks = 0;
    std::uint64_t access_units = 0;
    std::uint64_t klv_units = 0;
    std::uint64_t psi_repeats = 0;
    std::uint64_t pcrs = 0;
    std::uint64_t rejected = 0;  // empty units, KLV too long for one bounded PES
};

class TsMuxer {
  public:
    using Sink = std::function<void(std::span<const std::uint8_t> chunk)>;

    TsMuxer(MuxerOptions options, Codec codec, Sink sink);

    // Copies one access unit (Annex B). Its pts/dts are kept; a unit without pts gets none
    // (and PSI/PCR timing then follows the last known timestamp).
    void write_video(const AccessUnit& au);
    // One KLV payload (one or more whole local sets) in its own PES, with pts when given.
    void write_klv(std::span<const std::uint8_t> klv, std::optional<std::uint64_t> pts);
    // A new codec (the input changed): a new PMT version goes out before the next unit.
    void set_codec(Codec codec);
    // Hands out the partial chunk, if any.
    void flush();

    const MuxStats& stats() const { return stats_; }
    const MuxerOptions& options() const { return options_; }

  private:
    struct AdaptationFlags {
        std::optional<std::uint64_t> pcr_base;  // 90 kHz (extension 0)
        bool random_access = false;
        bool discontinuity = false;
    };

    void write_psi();
    void maybe_psi(std::optional<std::uint64_t> now, bool key_frame);
    void write_pes(std::uint16_t pid, std::span<const std::uint8_t> header,
                   std::span<const std::uint8_t> payload, const AdaptationFlags& first);
    void write_pcr_only(std::uint64_t pcr_base);
    std::uint64_t next_pcr(std::uint64_t dts, bool& discontinuity);
    // Appends one packet taking up to 184 - adaptation bytes of `payload`; returns how many.
    std::size_t packet(std::uint16_t pid, bool unit_start, const AdaptationFlags& flags,
                       std::span<const std::uint8_t> a, std::span<const std::uint8_t> b,
                       bool has_payload = true);
    std::uint8_t& cc_of(std::uint16_t pid);
    void emit_if_full();

    MuxerOptions options_;
    Codec codec_;
    Sink sink_;
    MuxStats stats_;
    std::uint8_t pmt_version_ = 0;
    bool psi_due_ = true;
    std::optional<std::uint64_t> last_psi_;  // 90 kHz stream time of the last PSI
    std::optional<std::uint64_t> last_pcr_;  // 90 kHz PCR base last written
    std::optional<std::uint64_t> clock_;     // latest DTS (or PTS) seen
    std::uint8_t cc_pat_ = 0, cc_pmt_ = 0, cc_video_ = 0, cc_klv_ = 0;
    std::vector<std::uint8_t> chunk_;
    std::vector<std::uint8_t> header_;  // PES header scratch
};

}  // namespace gimbal::video
