#include "video/pes.hpp"

#include "video/codec.hpp"

namespace gimbal::video {

namespace {

// 2.4.3.7: '4-bit prefix, TS[32..30], marker, TS[29..15], marker, TS[14..0], marker'.
std::uint64_t read_timestamp(std::span<const std::uint8_t> b) {
    return ((std::uint64_t{b[0]} & 0x0E) << 29) | (std::uint64_t{b[1]} << 22) |
           ((std::uint64_t{b[2]} & 0xFE) << 14) | (std::uint64_t{b[3]} << 7) | (b[4] >> 1);
}

void put_timestamp(std::vector<std::uint8_t>& out, std::uint8_t prefix, std::uint64_t ts) {
    ts %= pts_modulus;
    out.push_back(
        static_cast<std::uint8_t>((std::uint64_t{prefix} << 4) | ((ts >> 29) & 0x0E) | 1));
    out.push_back(static_cast<std::uint8_t>(ts >> 22));
    out.push_back(static_cast<std::uint8_t>(((ts >> 14) & 0xFE) | 1));
    out.push_back(static_cast<std::uint8_t>(ts >> 7));
    out.push_back(static_cast<std::uint8_t>(((ts << 1) & 0xFE) | 1));
}

bool has_optional_header(std::uint8_t id) {
    // Table 2-22: these stream_ids carry no PES header extension.
    return id != 0xBC && id != 0xBE && id != 0xBF && id != 0xF0 && id != 0xF1 && id != 0xFF &&
           id != 0xF2 && id != 0xF8;
}

}  // namespace

std::optional<PesHeader> parse_pes_header(std::span<const std::uint8_t> pes) {
    if (pes.size() < 6 || pes[0] != 0 || pes[1] != 0 || pes[2] != 1) return std::nullopt;
    PesHeader h;
    h.stream_id = pes[3];
    h.packet_length = (std::size_t{pes[4]} << 8) | pes[5];
    h.header_size = 6;
    if (!has_optional_header(h.stream_id)) return h;
    if (pes.size() < 9 || (pes[6] & 0xC0) != 0x80) return std::nullopt;
    h.data_alignment = (pes[6] & 0x04) != 0;
    const unsigned flags = pes[7] >> 6;
    const std::size_t data_length = pes[8];
    h.header_size = 9 + data_length;
    if (pes.size() < h.header_size) return std::nullopt;
    if (h.packet_length != 0 && h.packet_length + 6 < h.header_size) return std::nullopt;
    const auto opt = pes.subspan(9, data_length);
    if (flags & 2u) {
        if (opt.size() < 5) return std::nullopt;
        h.pts = read_timestamp(opt);
        if (flags == 3) {
            if (opt.size() < 10) return std::nullopt;
            h.dts = read_timestamp(opt.subspan(5));
        }
    }
    return h;
}

void write_pes_header(std::vector<std::uint8_t>& out, std::uint8_t id, std::size_t payload_size,
                      std::optional<std::uint64_t> pts, std::optional<std::uint64_t> dts,
                      bool data_alignment) {
    const bool with_dts = pts && dts && *dts != *pts;
    const std::size_t data_length = pts ? (with_dts ? 10 : 5) : 0;
    const std::size_t length = payload_size == 0 ? 0 : payload_size + 3 + data_length;
    const std::size_t written = length > 0xFFFF ? 0 : length;
    out.insert(out.end(), {0x00, 0x00, 0x01, id, static_cast<std::uint8_t>(written >> 8),
                           static_cast<std::uint8_t>(written & 0xFF)});
    out.push_back(data_alignment ? 0x84 : 0x80);
    out.push_back(pts ? (with_dts ? 0xC0 : 0x80) : 0x00);
    out.push_back(static_cast<std::uint8_t>(data_length));
    if (pts) put_timestamp(out, with_dts ? 3 : 2, *pts);
    if (with_dts) put_timestamp(out, 1, *dts);
}

}  // namespace gimbal::video
