// MPEG-TS demultiplexer: bytes in (any split: UDP datagrams, a file read, RTP payloads),
// access units of the program's H.264/H.265 video and its KLV metadata out.
//
// - Sync: a packet starts at 0x47; after junk or a lost sync byte the demuxer hunts for a
//   0x47 followed by another 188 bytes later, counting the skipped bytes as junk.
// - Program: the first program of the PAT whose PMT has video (stream_type 0x1B H.264 or
//   0x24 H.265), else the first with KLV. A changed PAT or PMT (any difference, not only a
//   new version: a restarted encoder starts again at version 0) is followed: new PIDs, new
//   codec, partial PES of the old PIDs dropped.
// - KLV: stream_type 0x06 with registration 'KLVA' (asynchronous, ST 1402) and
//   stream_type 0x15 with a KLVA metadata_descriptor (synchronous; PES payload of metadata
//   AU cells, 13818-1 2.12.4).
// - Units end when the PES does: at its PES_packet_length, at a packet with
//   adaptation-field stuffing (only the last packet of a PES may have it), or else when the
//   next PES starts; so a unit goes out with the datagram that completes it.
// - Loss: a continuity-counter gap (without the discontinuity indicator) or a transport
//   error on a PID marks its partial PES damaged; a damaged PES is dropped and counted,
//   never delivered. Duplicate packets (same CC) are ignored as 2.4.3.3 allows.
// - Bounds: every buffer that joins packets is bounded, whatever the stream: a video PES at
//   max_access_unit_bytes, a KLV PES at max_klv_pes_bytes, a synchronous metadata access unit
//   joined from fragments at max_metadata_au_bytes (codec.hpp); past a bound the unit is
//   dropped and counted. Memory kept after a large unit is given back.
// Pure: no clocks; timestamps are the stream's own (90 kHz PTS/DTS, 27 MHz PCR).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "video/codec.hpp"
#include "video/psi.hpp"
#include "video/ts_packet.hpp"

namespace gimbal::video {

struct DemuxStats {
    std::uint64_t bytes = 0;             // pushed
    std::uint64_t packets = 0;           // 188-byte packets found
    std::uint64_t junk_bytes = 0;        // skipped while hunting for sync
    std::uint64_t sync_losses = 0;       // times a packet did not start with 0x47
    std::uint64_t cc_errors = 0;         // continuity-counter gaps
    std::uint64_t transport_errors = 0;  // packets with transport_error_indicator set
    std::uint64_t bad_packets = 0;       // adaptation field longer than the packet
    std::uint64_t scrambled = 0;         // packets of a selected PID that are scrambled
    std::uint64_t psi_errors = 0;        // PAT/PMT sections with a bad CRC or layout
    std::uint64_t pes_errors = 0;        // PES whose header or layout does not parse
    std::uint64_t oversized_units = 0;   // video PES dropped at max_access_unit_bytes
    std::uint64_t oversized_klv = 0;     // KLV PES dropped at max_klv_pes_bytes
    std::uint64_t metadata_dropped = 0;  // sync metadata AUs dropped: over 64 KiB, or a middle
                                         // or last fragment without its first
    std::uint64_t dropped_units = 0;     // damaged PES (lost packets) not delivered
    std::uint64_t access_units = 0;
    std::uint64_t klv_units = 0;
    std::uint64_t program_changes = 0;  // the selected program's PIDs or codec changed
    std::uint64_t pcrs = 0;
};

// The program being followed.
struct ProgramInfo {
    std::uint16_t program_number = 0;
    std::uint16_t pmt_pid = 0;
    std::uint16_t pcr_pid = null_pid;
    std::optional<Codec> codec;  // with video_pid
    std::uint16_t video_pid = null_pid;
    std::optional<KlvCarriage> klv;  // with klv_pid
    std::uint16_t klv_pid = null_pid;
    friend bool operator==(const ProgramInfo&, const ProgramInfo&) = default;
};

class TsDemuxer {
  public:
    struct Handlers {
        std::function<void(const AccessUnit&)> access_unit;
        std::function<void(const KlvUnit&)> klv;
        std::function<void(const ProgramInfo&)> program;  // on every change of the program
    };

    explicit TsDemuxer(Handlers handlers);

    // Any number of bytes; handlers are called from inside.
    void push(std::span<const std::uint8_t> bytes);
    // End of stream: delivers a PES still open (an unbounded one whose last packet was
    // exactly full ends only when the next one starts).
    void flush();

    const DemuxStats& stats() const { return stats_; }
    const std::optional<ProgramInfo>& program() const { return program_; }
    std::optional<std::uint64_t> last_pcr() const { return last_pcr_; }
    // Bytes held back: an incomplete packet, or bytes waiting to confirm sync.
    std::size_t pending_bytes() const { return carry_.size(); }

  private:
    struct PesStream {
        std::vector<std::uint8_t> data;
        bool active = false;
        bool damaged = false;
    };

    std::size_t consume(std::span<const std::uint8_t> data);
    static bool overlaps_confirmed_packet(std::span<const std::uint8_t> data, std::size_t i);
    void packet(std::span<const std::uint8_t> bytes);
    void on_pat(std::span<const std::uint8_t> section);
    void on_pmt(std::uint16_t pid, std::span<const std::uint8_t> section);
    void select_program();
    void pes_packet(PesStream& s, const TsPacket& p, bool video);
    void finish_pes(PesStream& s, bool video);
    void deliver_pes(PesStream& s, bool video);
    void deliver_klv_cells(std::span<const std::uint8_t> payload, std::optional<std::uint64_t> pts);
    void damage(std::uint16_t pid);

    Handlers handlers_;
    DemuxStats stats_;
    std::vector<std::uint8_t> carry_;
    bool synced_ = false;
    std::array<std::uint8_t, 8192> last_cc_{};  // 0x10 = none seen yet

    SectionAssembler pat_assembler_;
    std::vector<std::uint8_t> pat_section_;            // the last PAT accepted, to see changes
    std::map<std::uint16_t, std::uint16_t> pmt_pids_;  // PMT PID -> program_number
    std::map<std::uint16_t, SectionAssembler> pmt_assemblers_;
    std::map<std::uint16_t, std::vector<std::uint8_t>> pmt_sections_;
    std::map<std::uint16_t, Pmt> pmts_;  // by PMT PID

    std::optional<ProgramInfo> program_;
    std::optional<std::uint64_t> last_pcr_;
    PesStream video_;
    PesStream klv_;
    std::vector<std::uint8_t> klv_fragment_;  // a metadata AU split over cells
    bool klv_fragment_open_ = false;
};

}  // namespace gimbal::video
