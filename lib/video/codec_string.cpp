#include "video/codec_string.hpp"

#include <cstdio>

#include "video/bit_reader.hpp"

namespace gimbal::video {

namespace {

std::string hex2(unsigned v) {
    char s[3];
    std::snprintf(s, sizeof s, "%02X", v & 0xFFu);
    return s;
}

// H.264 7.3.2.1.1: profile_idc, constraint_set flags and reserved bits, level_idc are the
// three bytes after the NAL header (no emulation prevention can fall in them: the first
// two are never both zero for a profile in use, but unescaping costs nothing).
std::optional<std::string> avc(ByteView nal) {
    const Bytes rbsp = unescape_rbsp(nal.subspan(1));
    if (rbsp.size() < 3) return std::nullopt;
    return "avc1." + hex2(rbsp[0]) + hex2(rbsp[1]) + hex2(rbsp[2]);
}

// H.265 7.3.2.2 and 7.3.3: after the 2-byte NAL header, one byte (VPS id, max sub-layers,
// temporal id nesting), then profile_tier_level's general part: profile space (2 bits),
// tier (1), profile_idc (5), 32 compatibility flags, 48 bits of constraint flags,
// level_idc (8). ISO/IEC 14496-15 E.3: "hvc1." + space letter (none, A, B, C) and
// profile_idc + "." + the compatibility flags bit-reversed in hex + "." + L or H and
// level_idc + the constraint bytes in hex, trailing zero bytes left out.
std::optional<std::string> hevc(ByteView nal) {
    if (nal.size() < 2) return std::nullopt;
    const Bytes rbsp = unescape_rbsp(nal.subspan(2));
    if (rbsp.size() < 1 + 1 + 4 + 6 + 1) return std::nullopt;
    const unsigned first = rbsp[1];
    const unsigned space = first >> 6;
    const bool high_tier = (first >> 5) & 1u;
    const unsigned profile = first & 0x1Fu;
    std::uint32_t flags = 0;
    for (int i = 0; i < 4; ++i) flags = (flags << 8) | rbsp[2 + static_cast<std::size_t>(i)];
    std::uint32_t reversed = 0;
    for (int i = 0; i < 32; ++i) reversed |= ((flags >> i) & 1u) << (31 - i);
    std::string s = "hvc1.";
    if (space > 0) s.push_back(static_cast<char>('A' + space - 1));
    char buf[16];
    std::snprintf(buf, sizeof buf, "%u.%X.", profile, reversed);
    s += buf;
    s.push_back(high_tier ? 'H' : 'L');
    s += std::to_string(rbsp[12]);
    std::size_t last =
        6;  // constraint bytes 6..11 of the general part; keep up to the last non-zero
    while (last > 0 && rbsp[6 + last - 1] == 0) --last;
    for (std::size_t i = 0; i < last; ++i) s += "." + hex2(rbsp[6 + i]);
    return s;
}

}  // namespace

std::optional<std::string> codec_string(Codec codec, ByteView sps_nal) {
    const std::uint8_t type = nal_type(codec, sps_nal);
    if (codec == Codec::h264) {
        if (type != h264::sps) return std::nullopt;
        return avc(sps_nal);
    }
    if (type != h265::sps) return std::nullopt;
    return hevc(sps_nal);
}

std::optional<std::string> find_codec_string(Codec codec, ByteView annexb_au) {
    for (const ByteView nal : split_annexb(annexb_au)) {
        if (auto s = codec_string(codec, nal)) return s;
    }
    return std::nullopt;
}

}  // namespace gimbal::video
