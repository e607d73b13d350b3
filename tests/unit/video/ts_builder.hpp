// Hand-built transport stream pieces for the video tests, written field by field from the
// ISO/IEC 13818-1 tables (2-2 packet header, 2-6 adaptation field, 2-21 PES, 2-30 PAT,
// 2-33 PMT) rather than with lib/video's own writers, so the tests check the library
// against the standard instead of against itself.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "video/crc32.hpp"

namespace gimbal::test {

using Bytes = std::vector<std::uint8_t>;

inline void put(Bytes& b, std::initializer_list<int> v) {
    for (int x : v) b.push_back(static_cast<std::uint8_t>(x));
}
inline void put(Bytes& b, const Bytes& v) {
    b.insert(b.end(), v.begin(), v.end());
}

// A long-form PSI section: table_id, section_syntax_indicator 1, '0', reserved '11',
// section_length, table_id_extension, reserved '11', version, current_next 1, section 0/0,
// body, CRC_32.
inline Bytes section(int table_id, int extension, int version, const Bytes& body) {
    Bytes s;
    const int length = static_cast<int>(body.size()) + 9;
    put(s, {table_id, 0xB0 | (length >> 8), length & 0xFF, extension >> 8, extension & 0xFF,
            0xC1 | (version << 1), 0, 0});
    put(s, body);
    const std::uint32_t crc = gimbal::video::crc32_mpeg2(s);
    put(s, {static_cast<int>(crc >> 24), static_cast<int>((crc >> 16) & 0xFF),
            static_cast<int>((crc >> 8) & 0xFF), static_cast<int>(crc & 0xFF)});
    return s;
}

inline Bytes pat(int program, int pmt_pid, int version = 0, int tsid = 1) {
    return section(0x00, tsid, version,
                   {static_cast<std::uint8_t>(program >> 8), static_cast<std::uint8_t>(program),
                    static_cast<std::uint8_t>(0xE0 | (pmt_pid >> 8)),
                    static_cast<std::uint8_t>(pmt_pid & 0xFF)});
}

struct EsEntry {
    int stream_type;
    int pid;
    Bytes descriptors;
};

inline Bytes pmt(int program, int pcr_pid, const std::vector<EsEntry>& streams, int version = 0,
                 const Bytes& program_info = {}) {
    Bytes body;
    const int info = static_cast<int>(program_info.size());
    put(body, {0xE0 | (pcr_pid >> 8), pcr_pid & 0xFF, 0xF0 | (info >> 8), info & 0xFF});
    put(body, program_info);
    for (const EsEntry& s : streams) {
        const int n = static_cast<int>(s.descriptors.size());
        put(body, {s.stream_type, 0xE0 | (s.pid >> 8), s.pid & 0xFF, 0xF0 | (n >> 8), n & 0xFF});
        put(body, s.descriptors);
    }
    return section(0x02, program, version, body);
}

inline const Bytes klva_registration = {0x05, 0x04, 'K', 'L', 'V', 'A'};
// metadata_descriptor (2.6.60): application format 0x0100 (ST 1402 uses it for general),
// metadata_format 0xFF + identifier 'KLVA', service id 0, decoder_config_flags 000,
// DSM-CC_flag 0, reserved.
inline const Bytes klva_metadata_descriptor = {0x26, 0x09, 0x01, 0x00, 0xFF, 'K',
                                               'L',  'V',  'A',  0x00, 0x0F};

struct PacketOptions {
    bool unit_start = false;
    int cc = 0;
    std::optional<std::uint64_t> pcr_base;
    bool random_access = false;
    bool discontinuity = false;
    bool transport_error = false;

    PacketOptions& start(bool v = true) {
        unit_start = v;
        return *this;
    }
    PacketOptions& counter(int v) {
        cc = v;
        return *this;
    }
    PacketOptions& pcr(std::uint64_t base) {
        pcr_base = base;
        return *this;
    }
    PacketOptions& rai(bool v = true) {
        random_access = v;
        return *this;
    }
    PacketOptions& disc(bool v = true) {
        discontinuity = v;
        return *this;
    }
};

// One 188-byte packet; payload beyond what fits is an error in the test, so the caller
// splits. Short payloads are padded with adaptation-field stuffing.
inline Bytes packet(int pid, const Bytes& payload, const PacketOptions& o = {}) {
    Bytes p;
    // One allocation up front: aarch64 GCC 12 at -O3 otherwise reports false
    // -Warray-bounds/-Wstringop-overread on the copy after the push_backs' regrowth.
    p.reserve(188);
    const bool flags = o.pcr_base || o.random_access || o.discontinuity;
    std::size_t af = flags ? 2 + (o.pcr_base ? 6 : 0) : 0;
    if (payload.size() + af < 184) af = 184 - payload.size();
    put(p, {0x47, (o.transport_error ? 0x80 : 0) | (o.unit_start ? 0x40 : 0) | (pid >> 8),
            pid & 0xFF, ((af ? 2 : 0) | (payload.empty() ? 0 : 1)) << 4 | o.cc});
    if (af) {
        p.push_back(static_cast<std::uint8_t>(af - 1));
        if (af > 1) {
            p.push_back(static_cast<std::uint8_t>((o.discontinuity ? 0x80 : 0) |
                                                  (o.random_access ? 0x40 : 0) |
                                                  (o.pcr_base ? 0x10 : 0)));
            if (o.pcr_base) {
                const std::uint64_t b = *o.pcr_base;
                put(p, {static_cast<int>(b >> 25) & 0xFF, static_cast<int>(b >> 17) & 0xFF,
                        static_cast<int>(b >> 9) & 0xFF, static_cast<int>(b >> 1) & 0xFF,
                        static_cast<int>((b & 1) << 7) | 0x7E, 0});
            }
            while (p.size() < 4 + af) p.push_back(0xFF);
        }
    }
    put(p, payload);
    return p;
}

// A PSI packet: pointer_field 0, the section, 0xFF fill.
inline Bytes psi_packet(int pid, const Bytes& sec, int cc = 0) {
    Bytes payload{0};
    put(payload, sec);
    while (payload.size() < 184) payload.push_back(0xFF);
    return packet(pid, payload, PacketOptions().start().counter(cc));
}

inline void put_timestamp(Bytes& b, int prefix, std::uint64_t ts) {
    put(b, {(prefix << 4) | static_cast<int>((ts >> 29) & 0x0E) | 1,
            static_cast<int>((ts >> 22) & 0xFF), static_cast<int>((ts >> 14) & 0xFE) | 1,
            static_cast<int>((ts >> 7) & 0xFF), static_cast<int>((ts << 1) & 0xFE) | 1});
}

// A PES packet: start code, stream_id, PES_packet_length (0 = unbounded when bounded is
// false), '10' + data_alignment, PTS/DTS flags, header length, timestamps, payload.
inline Bytes pes(int stream_id, const Bytes& payload, std::optional<std::uint64_t> pts,
                 std::optional<std::uint64_t> dts = std::nullopt, bool bounded = true) {
    Bytes b;
    const int opt = pts ? (dts ? 10 : 5) : 0;
    const int length = bounded ? static_cast<int>(payload.size()) + 3 + opt : 0;
    put(b, {0, 0, 1, stream_id, length >> 8, length & 0xFF, 0x84, pts ? (dts ? 0xC0 : 0x80) : 0x00,
            opt});
    if (pts) put_timestamp(b, dts ? 3 : 2, *pts);
    if (dts) put_timestamp(b, 1, *dts);
    put(b, payload);
    return b;
}

// Splits a PES over packets of `pid` with counters from cc; returns the packets.
inline std::vector<Bytes> pes_packets(int pid, const Bytes& pes_bytes, int& cc,
                                      const PacketOptions& first = {}) {
    std::vector<Bytes> out;
    std::size_t at = 0;
    bool start = true;
    while (at < pes_bytes.size()) {
        PacketOptions o = start ? first : PacketOptions{};
        o.unit_start = start;
        o.cc = cc;
        const std::size_t room = 184 - (o.pcr_base ? 8 : (o.random_access ? 2 : 0));
        const std::size_t n = std::min(room, pes_bytes.size() - at);
        out.push_back(packet(pid,
                             Bytes(pes_bytes.begin() + static_cast<long>(at),
                                   pes_bytes.begin() + static_cast<long>(at + n)),
                             o));
        at += n;
        cc = (cc + 1) & 15;
        start = false;
    }
    return out;
}

inline Bytes join(const std::vector<Bytes>& parts) {
    Bytes b;
    for (const Bytes& p : parts) put(b, p);
    return b;
}

// A 16-byte-key KLV packet (the ST 0601 UAS Datalink LS key) with a short value: the tests
// only need KLV bytes to carry, not a valid ST 0601 set.
inline Bytes klv_packet(std::uint8_t fill, std::size_t value_size = 8) {
    Bytes b = {0x06, 0x0E, 0x2B, 0x34, 0x02, 0x0B, 0x01, 0x01,
               0x0E, 0x01, 0x03, 0x01, 0x01, 0x00, 0x00, 0x00};
    if (value_size < 128) {
        b.push_back(static_cast<std::uint8_t>(value_size));
    } else {
        put(b, {0x82, static_cast<int>(value_size >> 8), static_cast<int>(value_size & 0xFF)});
    }
    b.insert(b.end(), value_size, fill);
    return b;
}

// A tiny Annex B access unit: AUD, (SPS, PPS, IDR) or a non-IDR slice, with filler so it
// spans several packets. The SPS is a real x264 one (640x360 baseline).
inline Bytes h264_au(bool key, std::size_t slice_size = 500, std::uint8_t fill = 0x55) {
    Bytes b = {0, 0, 0, 1, 0x09, 0xF0};
    if (key) {
        put(b, {0, 0, 0, 1});
        put(b, {0x67, 0x42, 0xc0, 0x16, 0xd9, 0x00, 0xa0, 0x2f, 0xf9, 0x70, 0x11, 0x00, 0x00,
                0x03, 0x00, 0x01, 0x00, 0x00, 0x03, 0x00, 0x1e, 0x0f, 0x16, 0x2e, 0x48});
        put(b, {0, 0, 0, 1, 0x68, 0xcb, 0x83, 0xcb, 0x20});
    }
    put(b, {0, 0, 0, 1, key ? 0x65 : 0x41, 0x88});
    b.insert(b.end(), slice_size, fill);
    return b;
}

}  // namespace gimbal::test
