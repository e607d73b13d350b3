// ICD section "Packets for external sensor inputs": optional data a client sends the gimbal.
#pragma once

#include <cstdint>
#include <string_view>

#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/fields.hpp"

namespace gimbal::orion {

// OrionAutopilotData (128): lets the gimbal refuse some operations (e.g. laser fire) on the
// ground.
struct AutopilotData {
    static constexpr std::uint8_t id = pkt::autopilot_data;
    static constexpr std::string_view name = "autopilot_data";
    static constexpr std::size_t min_length = 4;
    static constexpr std::size_t max_length = 4;

    bool is_flying = false;
    bool comm_good = false;
    std::int16_t agl = 0;  // m above ground, invalid if negative

    template <class V>
    void fields(V& v) {
        v.field("is_flying", is_flying, u8);
        v.field("comm_good", comm_good, u8);
        v.field("agl", agl, i16);
    }
};

// OrionExtHeadingData (210): an external heading observation for the INS.
// The ICD gives a minimum length of 4, yet only `pitch` is marked optional: the flag bits
// at bytes 4..5 are treated as optional too (absent = false) so a 4-byte packet decodes.
struct ExtHeadingData {
    static constexpr std::uint8_t id = pkt::ext_heading_data;
    static constexpr std::string_view name = "ext_heading_data";
    static constexpr std::size_t min_length = 4;
    static constexpr std::size_t max_length = 8;

    double ext_heading = 0;  // rad, true heading
    double noise = 0;        // rad, 0 = just shift the INS heading
    bool heading_in_gimbal_axis = false;
    bool heading_from_align = false;
    double pitch = 0;  // rad, of the vector used to compute the heading

    template <class V>
    void fields(V& v) {
        v.field("ext_heading", ext_heading, i16, 32767.0 / pi, Unit::radians);
        v.field("noise", noise, u16, 65535.0 / (2.0 * pi), Unit::radians);
        v.optional();
        v.bits("heading_in_gimbal_axis", heading_in_gimbal_axis, 1);
        v.bits("heading_from_align", heading_from_align, 1);
        v.reserved_bits(14);
        v.field("pitch", pitch, i16, 32767.0 / pi, Unit::radians);
    }
};

// OrionRangeData (214): range to the target, for the gimbal's target location. The keys are
// those of the contract's `range` command.
struct RangeData {
    static constexpr std::uint8_t id = pkt::range_data;
    static constexpr std::string_view name = "range_data";
    static constexpr std::size_t min_length = 7;
    static constexpr std::size_t max_length = 7;

    double range_m = 0;
    std::uint16_t max_age_ms = 0;  // the range expires after this
    RangeSource source = RangeSource::none;

    template <class V>
    void fields(V& v) {
        v.field("range_m", range_m, u32, 100.0);
        v.field("max_age_ms", max_age_ms, u16);
        v.field("source", source, u8);
    }
};

}  // namespace gimbal::orion

namespace gimbal::orion {
using ExternalPackets = PacketList<AutopilotData, ExtHeadingData, RangeData>;
}  // namespace gimbal::orion
