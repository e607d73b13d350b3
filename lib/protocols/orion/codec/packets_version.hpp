// ICD section "Packets used to determine manufacturing and software information about the
// gimbal". The gimbal sends these in reply to a zero-length request.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/fields.hpp"

namespace gimbal::orion {

// The layout the six board version packets share: a version string, then (for most boards)
// a part number and the board's on time. Boards whose packet lacks a field leave it empty;
// the JSON keys are those of the contract's `versions` object.
template <std::size_t VersionBytes, bool HasPartNumber, bool HasOnTime>
struct BoardVersion {
    static constexpr std::size_t part_number_bytes = 16;
    static constexpr std::size_t min_length =
        VersionBytes + (HasPartNumber ? part_number_bytes : 0);
    static constexpr std::size_t max_length = min_length + (HasOnTime ? 4 : 0);

    std::string version;
    std::string part_number;
    std::uint32_t on_time_min = 0;

    template <class V>
    void fields(V& v) {
        v.fixed_string("version", version, VersionBytes);
        if constexpr (HasPartNumber) v.fixed_string("part_number", part_number, part_number_bytes);
        if constexpr (HasOnTime) {
            v.optional();
            v.field("on_time_min", on_time_min, u32);
        }
    }
};

// OrionClevisVersion (37)
struct ClevisVersion : BoardVersion<16, true, true> {
    static constexpr std::uint8_t id = pkt::clevis_version;
    static constexpr std::string_view name = "clevis_version";
};

// OrionCrownVersion (40)
struct CrownVersion : BoardVersion<16, true, true> {
    static constexpr std::uint8_t id = pkt::crown_version;
    static constexpr std::string_view name = "crown_version";
};

// OrionPayloadVersion (41): the only one with a 24-byte version string.
struct PayloadVersion : BoardVersion<24, true, true> {
    static constexpr std::uint8_t id = pkt::payload_version;
    static constexpr std::string_view name = "payload_version";
};

// OrionTrackerVersion (44): no on time.
struct TrackerVersion : BoardVersion<16, true, false> {
    static constexpr std::uint8_t id = pkt::tracker_version;
    static constexpr std::string_view name = "tracker_version";
};

// OrionRetractVersion (248): version string only.
struct RetractVersion : BoardVersion<16, false, false> {
    static constexpr std::uint8_t id = pkt::retract_version;
    static constexpr std::string_view name = "retract_version";
};

// OrionLensCtlVersion (249): version string only.
struct LensCtlVersion : BoardVersion<16, false, false> {
    static constexpr std::uint8_t id = pkt::lensctl_version;
    static constexpr std::string_view name = "lensctl_version";
};

// OrionBoard (39): serial numbers and dates of one board. The ICD's two date structures
// (B7 year, B4 month, B5 day) are flattened into prefixed keys.
struct BoardInfo {
    static constexpr std::uint8_t id = pkt::board;
    static constexpr std::string_view name = "board";
    static constexpr std::size_t min_length = 20;
    static constexpr std::size_t max_length = 20;

    std::uint32_t board_sn = 0;
    std::uint32_t assembly_sn = 0;
    std::uint32_t config = 0;
    Board board = Board::none;
    std::uint8_t manufacture_year = 0;  // years after 2000
    std::uint8_t manufacture_month = 0;
    std::uint8_t manufacture_day = 0;
    std::uint8_t calibration_year = 0;  // years after 2000
    std::uint8_t calibration_month = 0;
    std::uint8_t calibration_day = 0;

    template <class V>
    void fields(V& v) {
        v.field("board_sn", board_sn, u32);
        v.field("assembly_sn", assembly_sn, u32);
        v.field("config", config, u32);
        v.reserved(u24);  // 3 x U8
        v.field("board", board, u8);
        v.bits("manufacture_year", manufacture_year, 7);
        v.bits("manufacture_month", manufacture_month, 4);
        v.bits("manufacture_day", manufacture_day, 5);
        v.bits("calibration_year", calibration_year, 7);
        v.bits("calibration_month", calibration_month, 4);
        v.bits("calibration_day", calibration_day, 5);
    }
};

}  // namespace gimbal::orion

namespace gimbal::orion {
using VersionPackets = PacketList<ClevisVersion, CrownVersion, PayloadVersion, TrackerVersion,
                                  RetractVersion, LensCtlVersion, BoardInfo>;
}  // namespace gimbal::orion
