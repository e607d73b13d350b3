#include "protocols/siyi/codec/frame.hpp"

#include <algorithm>
#include <cstring>

#include "protocols/siyi/codec/crc16.hpp"
#include "protocols/siyi/codec/framer.hpp"

namespace gimbal::siyi {

using framing::Probe;
using Verdict = Probe::Verdict;

void append_frame(std::vector<std::uint8_t>& out, Header header, std::uint8_t cmd,
                  std::span<const std::uint8_t> data) {
    const std::size_t len = std::min(data.size(), max_data_length);
    const std::size_t start = out.size();
    out.insert(out.end(),
               {stx0, stx1, header.ctrl, static_cast<std::uint8_t>(len & 0xFF),
                static_cast<std::uint8_t>(len >> 8), static_cast<std::uint8_t>(header.seq & 0xFF),
                static_cast<std::uint8_t>(header.seq >> 8), cmd});
    out.insert(out.end(), data.begin(), data.begin() + static_cast<long>(len));
    const std::uint16_t crc = crc16(std::span(out).subspan(start));
    out.push_back(static_cast<std::uint8_t>(crc & 0xFF));
    out.push_back(static_cast<std::uint8_t>(crc >> 8));
}

std::vector<std::uint8_t> frame_bytes(Header header, std::uint8_t cmd,
                                      std::span<const std::uint8_t> data) {
    std::vector<std::uint8_t> out;
    out.reserve(frame_overhead + data.size());
    append_frame(out, header, cmd, data);
    return out;
}

std::vector<std::uint8_t> frame_bytes(const Frame& frame) {
    return frame_bytes({frame.ctrl, frame.seq}, frame.cmd, frame.data.view());
}

std::size_t FrameRules::next_start(std::span<const std::uint8_t> data, std::size_t from) {
    // In a clean stream the next frame starts right at `from`; otherwise memchr finds it.
    if (from >= data.size() || data[from] == stx0) return from;
    const void* hit = std::memchr(data.data() + from, stx0, data.size() - from);
    return hit ? static_cast<std::size_t>(static_cast<const std::uint8_t*>(hit) - data.data())
               : data.size();
}

Probe FrameRules::probe(std::span<const std::uint8_t> d, Frame& out) {
    if (d.size() < 2) return {Verdict::need_more};
    if (d[1] != stx1) return {Verdict::no_frame};
    if (d.size() < header_size) return {Verdict::need_more};
    const std::size_t len = d[3] | (std::size_t{d[4]} << 8);
    if (len > max_data_length) return {Verdict::oversize};
    const std::size_t total = header_size + len + crc_size;
    if (d.size() < total) return {Verdict::need_more};
    const std::uint16_t crc = crc16(d.first(header_size + len));
    const std::size_t c = header_size + len;
    if (d[c] != (crc & 0xFF) || d[c + 1] != (crc >> 8)) return {Verdict::bad_checksum};
    out.ctrl = d[2];
    out.seq = static_cast<std::uint16_t>(d[5] | (d[6] << 8));
    out.cmd = d[7];
    out.data.size = len;
    std::memcpy(out.data.bytes.data(), d.data() + header_size, len);
    return {Verdict::frame, total};
}

std::optional<Frame> make_frame(std::span<const std::uint8_t> bytes) {
    if (bytes.empty() || !FrameRules::is_start(bytes[0])) return std::nullopt;
    Frame frame;
    const Probe p = FrameRules::probe(bytes, frame);
    if (p.verdict != Verdict::frame || p.size != bytes.size()) return std::nullopt;
    return frame;
}

}  // namespace gimbal::siyi
