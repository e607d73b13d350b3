#include "protocols/viewpro/codec/output_framer.hpp"

#include <algorithm>

#include "protocols/viewpro/codec/checksum.hpp"

namespace gimbal::viewpro {

using framing::Probe;
using Verdict = Probe::Verdict;

framing::Probe OutputFrameRules::probe(std::span<const std::uint8_t> d, OutputFrame& out) {
    if (d.size() < 2) return {Verdict::need_more};
    OutFormat format{};
    switch (d[1]) {
        case out1_id:
            format = OutFormat::out1;
            break;
        case out2_id:
            format = OutFormat::out2;
            break;
        case out3_id:
            format = OutFormat::out3;
            break;  // or OUT4, by byte 3
        default:
            return {Verdict::no_frame};
    }
    const std::size_t size = output_size(format);
    if (d.size() < size) return {Verdict::need_more};
    const auto frame = d.first(size);
    if (!checksum_ok(frame)) return {Verdict::bad_checksum};
    if (format == OutFormat::out3 && d[3] == out4_flag) format = OutFormat::out4;
    out.format = format;
    out.size = size;
    std::copy(frame.begin(), frame.end(), out.bytes.begin());
    return {Verdict::frame, size};
}

std::optional<OutputFrame> make_output_frame(std::span<const std::uint8_t> bytes) {
    if (bytes.empty() || !OutputFrameRules::is_start(bytes[0])) return std::nullopt;
    OutputFrame frame;
    const Probe p = OutputFrameRules::probe(bytes, frame);
    if (p.verdict != Verdict::frame || p.size != bytes.size()) return std::nullopt;
    return frame;
}

}  // namespace gimbal::viewpro
