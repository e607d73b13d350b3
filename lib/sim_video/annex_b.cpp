#include "sim_video/annex_b.hpp"

#include <cstddef>
#include <cstdio>

namespace gimbal::sim_video {

namespace {

// The index just past the next start code at or after `from`; bytes.size() when none.
std::size_t after_start_code(std::span<const std::uint8_t> bytes, std::size_t from,
                             std::size_t& code_at) {
    for (std::size_t i = from; i + 3 <= bytes.size(); ++i)
        if (bytes[i] == 0 && bytes[i + 1] == 0 && bytes[i + 2] == 1) {
            code_at = i > from && bytes[i - 1] == 0 ? i - 1 : i;
            return i + 3;
        }
    code_at = bytes.size();
    return bytes.size();
}

}  // namespace

std::vector<NalUnit> nal_units(std::span<const std::uint8_t> annex_b) {
    std::vector<NalUnit> out;
    std::size_t code_at = 0;
    std::size_t begin = after_start_code(annex_b, 0, code_at);
    while (begin < annex_b.size()) {
        const std::size_t next = after_start_code(annex_b, begin, code_at);
        const auto unit = annex_b.subspan(begin, code_at - begin);
        if (!unit.empty()) out.push_back({static_cast<std::uint8_t>(unit[0] & 0x1f), unit});
        begin = next;
    }
    return out;
}

std::optional<std::string> avc_codec_string(std::span<const std::uint8_t> annex_b) {
    for (const NalUnit& n : nal_units(annex_b)) {
        // profile_idc, constraint flags, level_idc follow the one-byte NAL header; none of
        // them can hold an emulation-prevention byte after a non-zero header.
        if (n.type != static_cast<std::uint8_t>(NalType::sps) || n.bytes.size() < 4) continue;
        char text[16];
        std::snprintf(text, sizeof text, "avc1.%02X%02X%02X", n.bytes[1], n.bytes[2], n.bytes[3]);
        return std::string(text);
    }
    return std::nullopt;
}

}  // namespace gimbal::sim_video
