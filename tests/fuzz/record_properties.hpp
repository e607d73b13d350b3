// What must hold for any input to the pcapng reader, shared by the libFuzzer target
// (fuzz_record_reader) and the unit test that replays its corpus and crash inputs.
// Returns "" when every property holds, else what broke.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "record/pcapng_reader.hpp"

namespace gimbal::fuzz {

inline std::string check_record_reader(std::span<const std::uint8_t> input) {
    namespace r = gimbal::record;
    const auto inside = [](std::span<const std::uint8_t> outer, std::span<const std::uint8_t> s) {
        return s.empty() ||
               (s.data() >= outer.data() && s.data() + s.size() <= outer.data() + outer.size());
    };
    r::PcapngReader reader(input);
    r::RecordedPacket packet;
    std::uint64_t count = 0;
    std::size_t last_offset = 0;
    while (reader.next(packet)) {
        ++count;
        if (!inside(input, packet.data)) return "packet data outside the input";
        if (!inside(packet.data, packet.pdu)) return "pdu outside the packet data";
        if (packet.interface_id >= reader.interfaces().size()) return "bad interface id";
        if (reader.offset() <= last_offset || reader.offset() > input.size())
            return "offset did not advance within the input";
        last_offset = reader.offset();
        if (!packet.pdu_error.empty() && !packet.pdu.empty()) return "pdu with an error";
    }
    if (reader.stop() == r::Stop::none) return "stopped without a reason";
    if (reader.stop() == r::Stop::end && reader.offset() != input.size())
        return "clean end before the end of the input";
    if (reader.stop() != r::Stop::end && reader.stop_message().empty()) return "no stop message";
    if (reader.packets() != count) return "packet count differs";
    if (reader.next(packet)) return "a packet after the stop";
    // The input cut where the reader stopped reads the same packets and ends cleanly
    // (unless nothing complete came before: an empty file reports itself as cut short).
    r::PcapngReader prefix(input.first(reader.offset()));
    std::uint64_t again = 0;
    while (prefix.next(packet)) ++again;
    if (again != count) return "the readable prefix gives a different packet count";
    if (reader.offset() > 0 && prefix.stop() != r::Stop::end)
        return "the readable prefix is not clean";
    return "";
}

}  // namespace gimbal::fuzz
