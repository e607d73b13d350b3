#include "protocols/viewpro/codec/input_framer.hpp"

#include <algorithm>

#include "protocols/viewpro/codec/checksum.hpp"

namespace gimbal::viewpro {

namespace {

using framing::Probe;
using Verdict = Probe::Verdict;

Probe probe_command(std::span<const std::uint8_t> d, InputFrame& out) {
    if (d.size() < 2) return {Verdict::need_more};
    if (d[1] != command_header1) return {Verdict::no_frame};
    if (d.size() < 3) return {Verdict::need_more};
    InputFrame::Kind kind{};
    switch (d[2]) {
        case set_mode_id:
            kind = InputFrame::Kind::mode;
            break;
        case yaw_shift_id:
            kind = InputFrame::Kind::yaw_shift;
            break;
        case pitch_shift_id:
            kind = InputFrame::Kind::pitch_shift;
            break;
        default:
            return {Verdict::no_frame};
    }
    if (d.size() < command_size) return {Verdict::need_more};
    if (d[4] != command_end) return {Verdict::bad_checksum};
    out.kind = kind;
    out.size = command_size;
    std::copy_n(d.begin(), command_size, out.bytes.begin());
    return {Verdict::frame, command_size};
}

Probe probe_in(std::span<const std::uint8_t> d, InputFrame& out) {
    if (d.size() < 2) return {Verdict::need_more};
    std::size_t size = 0;
    if (d[1] == in1_id)
        size = in1_size;
    else if (d[1] == in2_id)
        size = in2_size;  // == in3_size
    else
        return {Verdict::no_frame};
    if (d.size() < size) return {Verdict::need_more};
    const auto frame = d.first(size);
    if (!checksum_ok(frame)) return {Verdict::bad_checksum};
    out.kind = d[1] == in1_id     ? InputFrame::Kind::in1
               : d[3] == in3_flag ? InputFrame::Kind::in3
                                  : InputFrame::Kind::in2;
    out.size = size;
    std::copy(frame.begin(), frame.end(), out.bytes.begin());
    return {Verdict::frame, size};
}

}  // namespace

framing::Probe InputFrameRules::probe(std::span<const std::uint8_t> data, InputFrame& out) {
    return data[0] == input_header ? probe_in(data, out) : probe_command(data, out);
}

std::optional<InputFrame> make_input_frame(std::span<const std::uint8_t> bytes) {
    if (bytes.empty() || !InputFrameRules::is_start(bytes[0])) return std::nullopt;
    InputFrame frame;
    const Probe p = InputFrameRules::probe(bytes, frame);
    if (p.verdict != Verdict::frame || p.size != bytes.size()) return std::nullopt;
    return frame;
}

}  // namespace gimbal::viewpro
