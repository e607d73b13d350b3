// CRC-16/MCRF4XX and CRC_EXTRA: the checksum is pinned by its published check value and a
// bit-by-bit reference; each message's CRC_EXTRA is recomputed from its common.xml definition
// the way mavgen does, so a wrong field order or type in the codec shows up here too.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "helpers.hpp"

using namespace mavtest;

namespace {

// The reflected CRC-CCITT (poly 0x1021 -> 0x8408), one bit at a time: a different algorithm
// from the codec's byte-wise one.
std::uint16_t bitwise_crc(const Bytes& bytes, std::uint16_t crc = 0xFFFF) {
    for (const std::uint8_t b : bytes) {
        crc = static_cast<std::uint16_t>(crc ^ b);
        for (int bit = 0; bit < 8; ++bit)
            crc = static_cast<std::uint16_t>((crc & 1) ? (crc >> 1) ^ 0x8408 : crc >> 1);
    }
    return crc;
}

struct Field {
    std::string type;  // as in common.xml, uint8_t_mavlink_version written as uint8_t
    std::string name;
};

// mavgen: CRC of "NAME " then "type name " for every non-extension field in wire order,
// folded to one byte. (None of these messages has array fields, which would add a length.)
std::uint8_t crc_extra_from_definition(const std::string& name, const std::vector<Field>& fields) {
    std::uint16_t crc = crc16_mcrf4xx(name + " ");
    for (const Field& f : fields) {
        crc = crc16_mcrf4xx(f.type + " ", crc);
        crc = crc16_mcrf4xx(f.name + " ", crc);
    }
    return static_cast<std::uint8_t>((crc & 0xFF) ^ (crc >> 8));
}

std::size_t size_of(const std::string& type) {
    if (type == "uint64_t") return 8;
    if (type == "uint32_t" || type == "int32_t" || type == "float") return 4;
    if (type == "uint16_t" || type == "int16_t") return 2;
    return 1;
}

// Fields in declaration order as common.xml has them; the wire order is a stable sort by size.
std::vector<Field> wire_order(std::vector<Field> fields) {
    std::stable_sort(fields.begin(), fields.end(), [](const Field& a, const Field& b) {
        return size_of(a.type) > size_of(b.type);
    });
    return fields;
}

std::vector<Field> rc_channels_declared() {
    std::vector<Field> f{{"uint32_t", "time_boot_ms"}, {"uint8_t", "chancount"}};
    for (int i = 1; i <= 18; ++i) f.push_back({"uint16_t", "chan" + std::to_string(i) + "_raw"});
    f.push_back({"uint8_t", "rssi"});
    return f;
}

struct Definition {
    std::string name;
    std::vector<Field> declared;
    std::uint8_t crc_extra;  // the codec's constant
    std::size_t length;      // the codec's constant
    std::uint8_t published;  // MAVLINK_MSG_ID_<NAME>_CRC in the generated C headers
};

std::vector<Definition> definitions() {
    return {
        {"HEARTBEAT",
         {{"uint8_t", "type"},
          {"uint8_t", "autopilot"},
          {"uint8_t", "base_mode"},
          {"uint32_t", "custom_mode"},
          {"uint8_t", "system_status"},
          {"uint8_t", "mavlink_version"}},
         Heartbeat::crc_extra,
         Heartbeat::length,
         50},
        {"SYSTEM_TIME",
         {{"uint64_t", "time_unix_usec"}, {"uint32_t", "time_boot_ms"}},
         SystemTime::crc_extra,
         SystemTime::length,
         137},
        {"ATTITUDE",
         {{"uint32_t", "time_boot_ms"},
          {"float", "roll"},
          {"float", "pitch"},
          {"float", "yaw"},
          {"float", "rollspeed"},
          {"float", "pitchspeed"},
          {"float", "yawspeed"}},
         Attitude::crc_extra,
         Attitude::length,
         39},
        {"GLOBAL_POSITION_INT",
         {{"uint32_t", "time_boot_ms"},
          {"int32_t", "lat"},
          {"int32_t", "lon"},
          {"int32_t", "alt"},
          {"int32_t", "relative_alt"},
          {"int16_t", "vx"},
          {"int16_t", "vy"},
          {"int16_t", "vz"},
          {"uint16_t", "hdg"}},
         GlobalPositionInt::crc_extra,
         GlobalPositionInt::length,
         104},
        {"RC_CHANNELS", rc_channels_declared(), RcChannels::crc_extra, RcChannels::length, 118},
        // The camera component's messages without arrays (contract section 16).
        {"CAMERA_SETTINGS",
         {{"uint32_t", "time_boot_ms"}, {"uint8_t", "mode_id"}},
         CameraSettings::crc_extra,
         CameraSettings::length,
         146},
        {"CAMERA_CAPTURE_STATUS",
         {{"uint32_t", "time_boot_ms"},
          {"uint8_t", "image_status"},
          {"uint8_t", "video_status"},
          {"float", "image_interval"},
          {"uint32_t", "recording_time_ms"},
          {"float", "available_capacity"}},
         CameraCaptureStatus::crc_extra,
         CameraCaptureStatus::length,
         12},
        {"VIDEO_STREAM_STATUS",
         {{"uint8_t", "stream_id"},
          {"uint16_t", "flags"},
          {"float", "framerate"},
          {"uint16_t", "resolution_h"},
          {"uint16_t", "resolution_v"},
          {"uint32_t", "bitrate"},
          {"uint16_t", "rotation"},
          {"uint16_t", "hfov"}},
         VideoStreamStatus::crc_extra,
         VideoStreamStatus::length,
         59},
        {"CAMERA_TRACKING_GEO_STATUS",
         {{"uint8_t", "tracking_status"},
          {"int32_t", "lat"},
          {"int32_t", "lon"},
          {"float", "alt"},
          {"float", "h_acc"},
          {"float", "v_acc"},
          {"float", "vel_n"},
          {"float", "vel_e"},
          {"float", "vel_d"},
          {"float", "vel_acc"},
          {"float", "dist"},
          {"float", "hdg"},
          {"float", "hdg_acc"}},
         CameraTrackingGeoStatus::crc_extra,
         CameraTrackingGeoStatus::length,
         18},
    };
}

}  // namespace

TEST_CASE("CRC-16/MCRF4XX has the published check value", "[mavlink][crc]") {
    const std::string check = "123456789";
    CHECK(crc16_mcrf4xx(check) == 0x6F91);
    const Bytes bytes(check.begin(), check.end());
    CHECK(crc16_mcrf4xx(bytes) == 0x6F91);
    CHECK(bitwise_crc(bytes) == 0x6F91);
    CHECK(crc16_mcrf4xx(Bytes{}) == 0xFFFF);  // no final XOR
}

TEST_CASE("CRC-16/MCRF4XX equals the bitwise reference and can be continued", "[mavlink][crc]") {
    std::mt19937 rng(11);
    for (std::size_t n = 0; n <= 300; ++n) {
        Bytes bytes(n);
        for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
        const std::uint16_t whole = crc16_mcrf4xx(bytes);
        CHECK(whole == bitwise_crc(bytes));
        const std::size_t cut = n / 3;
        const std::uint16_t first = crc16_mcrf4xx(std::span<const std::uint8_t>(bytes).first(cut));
        CHECK(crc16_mcrf4xx(std::span<const std::uint8_t>(bytes).subspan(cut), first) == whole);
    }
}

TEST_CASE("CRC_EXTRA of each message follows from its common.xml definition", "[mavlink][crc]") {
    for (const Definition& d : definitions()) {
        CAPTURE(d.name);
        const std::vector<Field> wire = wire_order(d.declared);
        const std::uint8_t derived = crc_extra_from_definition(d.name, wire);
        CHECK(derived == d.published);
        CHECK(d.crc_extra == d.published);
        std::size_t length = 0;
        for (const Field& f : wire) length += size_of(f.type);
        CHECK(d.length == length);
    }
    // Declaration order would give a different CRC_EXTRA where the sort moves fields.
    const auto defs = definitions();
    CHECK(crc_extra_from_definition(defs[0].name, defs[0].declared) != defs[0].published);
    CHECK(crc_extra_from_definition(defs[4].name, defs[4].declared) != defs[4].published);
}

TEST_CASE("the message table knows exactly the five messages", "[mavlink][crc]") {
    const std::vector<std::pair<std::uint32_t, std::uint8_t>> known{
        {0, 50}, {2, 137}, {30, 39}, {33, 104}, {65, 118}};
    for (const auto& [id, extra] : known) {
        const MessageInfo* info = find_message(id);
        REQUIRE(info != nullptr);
        CHECK(info->crc_extra == extra);
    }
    for (const std::uint32_t id : {1u, 24u, 31u, 74u, 253u, 256u, 0x10000u, 0xFFFFFFu})
        CHECK(find_message(id) == nullptr);
}
