// Golden tests for the configuration, version and external-sensor packets
// (packets_config.hpp, packets_version.hpp, packets_external.hpp). Every golden vector is
// written by hand from the ICD tables, one comment per field: "offset: field = value".
#include <catch2/catch.hpp>
#include <initializer_list>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"

using namespace gimbal::orion;
using Bytes = std::vector<std::uint8_t>;
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

constexpr double deg = 180.0 / pi;
constexpr double i16_pi = pi / 32767.0;  // one step of an I16 "scaled by 32767/pi"

Bytes bytes_of(const Payload& p) {
    return Bytes(p.bytes.begin(), p.bytes.begin() + static_cast<long>(p.size));
}

Bytes head(const Bytes& b, std::size_t n) {
    return Bytes(b.begin(), b.begin() + static_cast<long>(n));
}

std::set<std::string> keys_of(const json& j) {
    std::set<std::string> keys;
    for (const auto& item : j.items()) keys.insert(item.key());
    return keys;
}

// Decodes a full-length golden vector and requires the encoder to give the same bytes back.
template <class P>
P decode_golden(const Bytes& golden) {
    REQUIRE(golden.size() == P::max_length);
    const auto d = decode<P>(golden);
    INFO(to_string(d.error));
    REQUIRE(d.ok);
    CHECK(bytes_of(encode(d.value)) == golden);
    return d.value;
}

// One byte short of the minimum is an error naming the field that did not fit.
template <class P>
void check_one_short_fails(const Bytes& golden, const std::string& field) {
    const auto d = decode<P>(head(golden, P::min_length - 1));
    CHECK_FALSE(d.ok);
    CHECK_THAT(to_string(d.error), Contains("'" + field + "'"));
}

// Exactly the minimum decodes; the caller checks the optional fields' defaults.
template <class P>
P decode_minimum(const Bytes& golden) {
    const auto d = decode<P>(head(golden, P::min_length));
    INFO(to_string(d.error));
    REQUIRE(d.ok);
    return d.value;
}

// Newer firmware may append fields: unknown trailing bytes are ignored.
template <class P>
void check_extra_bytes_ignored(const Bytes& golden) {
    Bytes longer = golden;
    longer.insert(longer.end(), {0xA5, 0x5A, 0xFF, 0x01});
    const auto d = decode<P>(longer);
    REQUIRE(d.ok);
    CHECK(bytes_of(encode(d.value)) == golden);
}

// to_json then from_json gives a packet that encodes to the same bytes.
template <class P>
void check_json_round_trip(const P& packet) {
    P back;
    JsonError err;
    const json j = to_json(packet);
    INFO(j.dump());
    REQUIRE(from_json(j, back, err));
    CHECK(bytes_of(encode(back)) == bytes_of(encode(packet)));
}

template <class P>
void check_json_rejected(const json& j, const std::string& code, const std::string& key) {
    P packet;
    JsonError err;
    INFO(j.dump());
    CHECK_FALSE(from_json(j, packet, err));
    CHECK(err.code == code);
    CHECK_THAT(err.message, Contains(key));
}

template <class P>
void check_packet_listed() {
    CHECK(packet_name(P::id) == P::name);
    std::uint8_t id = 0;
    REQUIRE(packet_id(P::name, id));
    CHECK(id == P::id);
}

using EnumTable = std::initializer_list<std::pair<int, std::string_view>>;

// Every ICD value maps to its name and back, through the name table and through a packet's
// JSON (at `pointer`); a value the table does not know is written as its number.
template <class P, class E, class Member>
void check_enum(P packet, Member member, const std::string& pointer, EnumTable expected,
                int unknown) {
    CHECK(enum_names(E{}).size() == expected.size());
    const json::json_pointer at(pointer);
    for (const auto& [value, name] : expected) {
        INFO(name);
        const auto e = static_cast<E>(value);
        CHECK(enum_name(e) == name);
        E from_name{};
        REQUIRE(enum_from_name(name, from_name));
        CHECK(from_name == e);

        member(packet) = e;
        const json j = to_json(packet);
        CHECK(j.at(at) == name);
        P back;
        JsonError err;
        REQUIRE(from_json(j, back, err));
        CHECK(member(back) == e);
    }
    member(packet) = static_cast<E>(unknown);
    const json j = to_json(packet);
    CHECK(j.at(at) == unknown);
    P back;
    JsonError err;
    REQUIRE(from_json(j, back, err));  // a number is accepted as the raw value
    CHECK(member(back) == static_cast<E>(unknown));
}

}  // namespace

#include "golden_config.hpp"

using namespace gimbal::orion::golden_vectors;

// --- OrionUartConfig -------------------------------------------------------------------------

TEST_CASE("uart_config golden bytes decode and re-encode", "[orion][packets][config]") {
    check_packet_listed<UartConfig>();
    const auto p = decode_golden<UartConfig>(uart_config_golden);
    CHECK(p.port == UserDataPort::fp1);
    CHECK(p.baud == 115200);
    CHECK(p.protocol == UartProtocol::orion);
    CHECK(p.temporary);
    check_extra_bytes_ignored<UartConfig>(uart_config_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"port", "baud", "protocol", "temporary"});
    CHECK(j["port"] == "fp1");
    CHECK(j["protocol"] == "orion");
    CHECK(j["temporary"] == true);
    check_json_round_trip(p);
}

TEST_CASE("uart_config length limits", "[orion][packets][config]") {
    check_one_short_fails<UartConfig>(uart_config_golden, "protocol");
    const auto p = decode_minimum<UartConfig>(uart_config_golden);
    CHECK(p.protocol == UartProtocol::orion);
    CHECK_FALSE(p.temporary);  // ICD default 0
}

TEST_CASE("uart_config JSON rejects bad input", "[orion][packets][config][json]") {
    check_json_rejected<UartConfig>({{"baud", 9600}, {"parity", "none"}}, "bad_request", "parity");
    check_json_rejected<UartConfig>({{"baud", "fast"}}, "bad_request", "baud");
    check_json_rejected<UartConfig>({{"baud", 16777216}}, "out_of_range", "baud");
    check_json_rejected<UartConfig>({{"protocol", "zmodem"}}, "bad_request", "protocol");
    check_json_rejected<UartConfig>({{"temporary", 1}}, "bad_request", "temporary");
}

TEST_CASE("uart_config protocol names", "[orion][packets][config][enum]") {
    check_enum<UartConfig, UartProtocol>(
        UartConfig{}, [](UartConfig& p) -> UartProtocol& { return p.protocol; }, "/protocol",
        {{0, "no_change"},     {1, "none"},          {2, "default"},    {3, "orion"},
         {4, "clevis"},        {5, "clevis_raw"},    {6, "nmea_gps"},   {7, "ublox_gps"},
         {8, "novatel_gps"},   {9, "mavlink_gps"},   {10, "um7_mag"},   {11, "sightline_video"},
         {12, "sensonor_imu"}, {13, "dmu11_imu"},    {14, "discovery"}, {15, "airrobot"},
         {16, "proprietary1"}, {17, "proprietary2"}, {18, "flir"},      {19, "epson_imu"},
         {20, "piksi"},        {21, "wepilot"}},
        22);
}

// --- OrionLimitsData -------------------------------------------------------------------------

TEST_CASE("limits golden bytes decode and re-encode", "[orion][packets][config]") {
    check_packet_listed<Limits>();
    const auto p = decode_golden<Limits>(limits_golden);
    CHECK(p.min_pos[0] == Approx(-3.0));
    CHECK(p.min_pos[1] == Approx(-1.5));
    CHECK(p.max_pos[0] == Approx(3.0));
    CHECK(p.max_pos[1] == Approx(1.5));
    CHECK(p.max_vel[0] == Approx(2.5));
    CHECK(p.max_vel[1] == Approx(1.25));
    CHECK(p.max_accel[0] == Approx(20.0));
    CHECK(p.max_accel[1] == Approx(10.0));
    CHECK(p.cont_cur[0] == Approx(1.2));
    CHECK(p.cont_cur[1] == Approx(0.8));
    CHECK(p.peak_cur[0] == Approx(3.5));
    CHECK(p.peak_cur[1] == Approx(2.75));
    CHECK(p.peak_cur_time_s[0] == Approx(0.5));
    CHECK(p.peak_cur_time_s[1] == Approx(0.25));
    CHECK(p.init_cur[0] == Approx(0.6));
    CHECK(p.init_cur[1] == Approx(0.4));
    CHECK(p.max_power[0] == Approx(40.0));
    CHECK(p.max_power[1] == Approx(30.0));
    check_extra_bytes_ignored<Limits>(limits_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"min_pos", "max_pos", "max_vel", "max_accel",
                                              "cont_cur", "peak_cur", "peak_cur_time_s", "init_cur",
                                              "max_power"});
    CHECK(j["min_pos"][0].get<double>() == Approx(-3.0 * deg));  // degrees
    CHECK(j["max_pos"][1].get<double>() == Approx(1.5 * deg));
    CHECK(j["max_vel"][0].get<double>() == Approx(2.5 * deg));  // degrees/s
    CHECK(j["max_accel"][0].get<double>() == Approx(20.0 * deg));
    CHECK(j["cont_cur"][0].get<double>() == Approx(1.2));  // amps unchanged
    check_json_round_trip(p);
}

TEST_CASE("limits length limits", "[orion][packets][config]") {
    check_one_short_fails<Limits>(limits_golden, "init_cur");
    const auto p = decode_minimum<Limits>(limits_golden);
    CHECK(p.init_cur[1] == Approx(0.4));
    CHECK(p.max_power == std::array<double, 2>{0.0, 0.0});  // ICD default: no limit
    // Half of the optional MaxPower array is not a field: it stays at its default.
    const auto partial = decode<Limits>(head(limits_golden, 33));
    REQUIRE(partial.ok);
    CHECK(partial.value.max_power == std::array<double, 2>{0.0, 0.0});
}

TEST_CASE("limits JSON rejects bad input", "[orion][packets][config][json]") {
    check_json_rejected<Limits>({{"min_pos", {-10.0, -5.0}}, {"min_tilt", 1}}, "bad_request",
                                "min_tilt");
    check_json_rejected<Limits>({{"min_pos", {1.0, 2.0, 3.0}}}, "bad_request", "min_pos");
    check_json_rejected<Limits>({{"cont_cur", "high"}}, "bad_request", "cont_cur");
    // 65.535 rad/s is the U16 ceiling: about 3754.9 degrees/s.
    check_json_rejected<Limits>({{"max_vel", {10.0, 4000.0}}}, "out_of_range", "max_vel[1]");
    check_json_rejected<Limits>({{"max_power", {-1, 0}}}, "out_of_range", "max_power[0]");
}

// --- InsOptions --------------------------------------------------------------------------

TEST_CASE("ins_options golden bytes decode and re-encode", "[orion][packets][config]") {
    check_packet_listed<InsOptions>();
    const auto p = decode_golden<InsOptions>(ins_options_golden);
    CHECK(p.enable_platform_rotation);
    CHECK(p.enable_course_is_heading);
    CHECK(p.disable_magnetometer);
    CHECK(p.disable_gps);
    CHECK(p.reset_ins);
    CHECK(p.disable_gps_clock_error);
    CHECK(p.enable_accel_bias);
    CHECK(p.enable_tightly_coupled);
    CHECK(p.use_phase_for_velocity);
    CHECK(p.disable_l1);
    CHECK(p.disable_l2);
    CHECK(p.disable_l5);
    CHECK(p.elevation_mask_code == 9);
    CHECK(p.enable_payload_ins);
    CHECK(p.enable_non_linear_heading);
    CHECK(p.enable_sensonor_mv);
    CHECK(p.enable_hd25_payload_ins);
    CHECK(p.optical_flow_setting == 5);
    CHECK(p.gimbal_to_platform_euler[0] == Approx(8192 * i16_pi));
    CHECK(p.gimbal_to_platform_euler[1] == Approx(-4096 * i16_pi));
    CHECK(p.gimbal_to_platform_euler[2] == Approx(16384 * i16_pi));
    CHECK(p.initial_heading == Approx(4096 * i16_pi));
    CHECK(p.gps_lever_arm[0] == Approx(0.5));
    CHECK(p.gps_lever_arm[1] == Approx(-0.25));
    CHECK(p.gps_lever_arm[2] == Approx(1.0));
    CHECK(p.heading_observation_bias_angle == Approx(-1024 * i16_pi));
    CHECK(p.second_gps_lever_arm[0] == Approx(1.5));
    CHECK(p.second_gps_lever_arm[1] == Approx(-1.0));
    CHECK(p.second_gps_lever_arm[2] == Approx(0.125));
    CHECK(p.align_heading_noise == Approx(2048 * pi / 65535.0));
    check_extra_bytes_ignored<InsOptions>(ins_options_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"enable_platform_rotation",
                                              "enable_course_is_heading",
                                              "disable_magnetometer",
                                              "disable_gps",
                                              "reset_ins",
                                              "disable_gps_clock_error",
                                              "enable_accel_bias",
                                              "enable_tightly_coupled",
                                              "use_phase_for_velocity",
                                              "disable_l1",
                                              "disable_l2",
                                              "disable_l5",
                                              "elevation_mask_code",
                                              "enable_payload_ins",
                                              "enable_non_linear_heading",
                                              "enable_sensonor_mv",
                                              "enable_hd25_payload_ins",
                                              "optical_flow_setting",
                                              "gimbal_to_platform_euler",
                                              "initial_heading",
                                              "gps_lever_arm",
                                              "heading_observation_bias_angle",
                                              "second_gps_lever_arm",
                                              "align_heading_noise"});
    CHECK(j["enable_platform_rotation"] == true);
    CHECK(j["elevation_mask_code"] == 9);
    CHECK(j["gimbal_to_platform_euler"][2].get<double>() == Approx(16384 * i16_pi * deg));
    CHECK(j["initial_heading"].get<double>() == Approx(4096 * i16_pi * deg));
    CHECK(j["gps_lever_arm"][1].get<double>() == Approx(-0.25));  // metres unchanged
    CHECK(j["align_heading_noise"].get<double>() == Approx(2048 * pi / 65535.0 * deg));
    check_json_round_trip(p);
}

TEST_CASE("ins_options bit positions follow the ICD, MSB first", "[orion][packets][config]") {
    const Bytes bytes{
        0xA5,  // 1010 0101: platformRotation, disableMagnetometer, disableGpsClockError,
               //            enableTightlyCoupled
        0x5C,  // 0101 1100: disableL1, disableL5; elevationMask = 12
        0xA3,  // 1010 0011: enablePayloadIns, enableSensonorMV; opticalFlowSetting = 3
        0x00,  // reserved
        0, 0, 0, 0, 0, 0, 0, 0,  // 4..11: euler angles and initial heading = 0
    };
    const auto d = decode<InsOptions>(bytes);
    REQUIRE(d.ok);
    const auto& p = d.value;
    CHECK(p.enable_platform_rotation);
    CHECK_FALSE(p.enable_course_is_heading);
    CHECK(p.disable_magnetometer);
    CHECK_FALSE(p.disable_gps);
    CHECK_FALSE(p.reset_ins);
    CHECK(p.disable_gps_clock_error);
    CHECK_FALSE(p.enable_accel_bias);
    CHECK(p.enable_tightly_coupled);
    CHECK_FALSE(p.use_phase_for_velocity);
    CHECK(p.disable_l1);
    CHECK_FALSE(p.disable_l2);
    CHECK(p.disable_l5);
    CHECK(p.elevation_mask_code == 12);
    CHECK(p.enable_payload_ins);
    CHECK_FALSE(p.enable_non_linear_heading);
    CHECK(p.enable_sensonor_mv);
    CHECK_FALSE(p.enable_hd25_payload_ins);
    CHECK(p.optical_flow_setting == 3);
    // Encoding writes every optional field: 12 bytes become 28, the first 12 unchanged.
    const Bytes out = bytes_of(encode(p));
    REQUIRE(out.size() == InsOptions::max_length);
    CHECK(head(out, 12) == bytes);
}

TEST_CASE("ins_options length limits", "[orion][packets][config]") {
    check_one_short_fails<InsOptions>(ins_options_golden, "initial_heading");
    const auto p = decode_minimum<InsOptions>(ins_options_golden);
    CHECK(p.initial_heading == Approx(4096 * i16_pi));
    CHECK(p.gps_lever_arm == std::array<double, 3>{0, 0, 0});
    CHECK(p.heading_observation_bias_angle == 0.0);
    CHECK(p.second_gps_lever_arm == std::array<double, 3>{0, 0, 0});
    CHECK(p.align_heading_noise == 0.0);
}

TEST_CASE("ins_options JSON rejects bad input", "[orion][packets][config][json]") {
    check_json_rejected<InsOptions>({{"disable_gps", true}, {"disable_glonass", true}},
                                    "bad_request", "disable_glonass");
    check_json_rejected<InsOptions>({{"reset_ins", 1}}, "bad_request", "reset_ins");
    check_json_rejected<InsOptions>({{"optical_flow_setting", 16}}, "out_of_range",
                                    "optical_flow_setting");
    check_json_rejected<InsOptions>({{"initial_heading", 181.0}}, "out_of_range",
                                    "initial_heading");
    check_json_rejected<InsOptions>({{"gps_lever_arm", {0.0, 0.0, 33.0}}}, "out_of_range",
                                    "gps_lever_arm[2]");
}

// --- OrionNetworkSettings ----------------------------------------------------------------

TEST_CASE("network_settings golden bytes decode and re-encode", "[orion][packets][config]") {
    check_packet_listed<NetworkSettings>();
    const auto p = decode_golden<NetworkSettings>(network_settings_golden);
    CHECK(p.ip == 0xC0A80114u);
    CHECK(p.mask == 0xFFFFFF00u);
    CHECK(p.gateway == 0xC0A80101u);
    CHECK(p.low_delay);
    CHECK(p.mtu == 1400);
    check_extra_bytes_ignored<NetworkSettings>(network_settings_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"ip", "mask", "gateway", "low_delay", "mtu"});
    CHECK(j["ip"] == "192.168.1.20");
    CHECK(j["mask"] == "255.255.255.0");
    CHECK(j["gateway"] == "192.168.1.1");
    check_json_round_trip(p);
}

TEST_CASE("network_settings: the ICD's byte form gives the same addresses",
          "[orion][packets][config]") {
    // OrionNetworkByteSettings: each address as U8[4], first byte = first dotted number.
    const Bytes byte_form{
        10,  0,   0,   7,  // 0..3: Ip[4] = 10.0.0.7
        255, 255, 0,   0,  // 4..7: Mask[4] = 255.255.0.0
        10,  0,   254, 1,  // 8..11: Gateway[4] = 10.0.254.1
    };
    const auto d = decode<NetworkSettings>(byte_form);
    REQUIRE(d.ok);
    const json j = to_json(d.value);
    CHECK(j["ip"] == "10.0.0.7");
    CHECK(j["mask"] == "255.255.0.0");
    CHECK(j["gateway"] == "10.0.254.1");
    // ...and a dotted string from a client encodes to exactly those bytes.
    NetworkSettings p;
    JsonError err;
    REQUIRE(from_json(json{{"ip", "10.0.0.7"}, {"mask", "255.255.0.0"}, {"gateway", "10.0.254.1"}},
                      p, err));
    CHECK(head(bytes_of(encode(p)), 12) == byte_form);
}

TEST_CASE("network_settings length limits", "[orion][packets][config]") {
    check_one_short_fails<NetworkSettings>(network_settings_golden, "gateway");
    const auto p = decode_minimum<NetworkSettings>(network_settings_golden);
    CHECK(p.gateway == 0xC0A80101u);
    CHECK_FALSE(p.low_delay);
    CHECK(p.mtu == 0);
}

TEST_CASE("network_settings JSON rejects bad input", "[orion][packets][config][json]") {
    check_json_rejected<NetworkSettings>({{"ip", "10.0.0.1"}, {"dns", "8.8.8.8"}}, "bad_request",
                                         "dns");
    check_json_rejected<NetworkSettings>({{"ip", 3232235796u}}, "bad_request", "ip");
    check_json_rejected<NetworkSettings>({{"mask", "255.255.256.0"}}, "bad_request", "mask");
    check_json_rejected<NetworkSettings>({{"gateway", "10.0.0"}}, "bad_request", "gateway");
    check_json_rejected<NetworkSettings>({{"mtu", 65536}}, "out_of_range", "mtu");
}

// --- OrionNetworkVideo -------------------------------------------------------------------

TEST_CASE("network_video golden bytes decode and re-encode", "[orion][packets][config]") {
    check_packet_listed<NetworkVideo>();
    const auto p = decode_golden<NetworkVideo>(network_video_golden);
    CHECK(p.dest_ip == 0xEF010203u);
    CHECK(p.port == 15004);
    CHECK(p.bitrate == 4000000u);
    CHECK(p.ttl == 5);
    CHECK(p.stream_type == StreamType::mjpeg);
    CHECK(p.mjpeg_quality == 80);
    CHECK(p.save_settings);
    CHECK(p.ts_packet_count == 7);
    check_extra_bytes_ignored<NetworkVideo>(network_video_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"dest_ip", "port", "bitrate", "ttl", "stream_type",
                                              "mjpeg_quality", "save_settings", "ts_packet_count"});
    CHECK(j["dest_ip"] == "239.1.2.3");
    CHECK(j["stream_type"] == "mjpeg");
    CHECK(j["save_settings"] == true);
    CHECK(j["ts_packet_count"] == 7);
    check_json_round_trip(p);
}

TEST_CASE("network_video: the ICD's byte form gives the same address", "[orion][packets][config]") {
    const Bytes byte_form{
        192,  168,  1, 20,  // 0..3: DestIp[4] = 192.168.1.20 (OrionNetworkByteVideo)
        0x13, 0x88,         // 4..5: Port = 5000
    };
    const auto d = decode<NetworkVideo>(byte_form);
    REQUIRE(d.ok);
    CHECK(d.value.dest_ip == 0xC0A80114u);  // same value as the U32 form of the ICD
    CHECK(to_json(d.value)["dest_ip"] == "192.168.1.20");
    CHECK(d.value.port == 5000);
}

TEST_CASE("network_video length limits and optional defaults", "[orion][packets][config]") {
    check_one_short_fails<NetworkVideo>(network_video_golden, "port");
    const auto p = decode_minimum<NetworkVideo>(network_video_golden);
    CHECK(p.port == 15004);
    CHECK(p.bitrate == 0);
    CHECK(p.ttl == -1);
    CHECK(p.stream_type == StreamType::h264);
    CHECK(p.mjpeg_quality == 30);
    CHECK_FALSE(p.save_settings);
    CHECK(p.ts_packet_count == 0);
    // 13 bytes: everything but the last bit-field byte.
    const auto d = decode<NetworkVideo>(head(network_video_golden, 13));
    REQUIRE(d.ok);
    CHECK(d.value.mjpeg_quality == 80);
    CHECK_FALSE(d.value.save_settings);
    CHECK(d.value.ts_packet_count == 0);
}

TEST_CASE("network_video JSON rejects bad input", "[orion][packets][config][json]") {
    check_json_rejected<NetworkVideo>({{"port", 5000}, {"codec", "h265"}}, "bad_request", "codec");
    check_json_rejected<NetworkVideo>({{"port", "5000"}}, "bad_request", "port");
    check_json_rejected<NetworkVideo>({{"port", 65536}}, "out_of_range", "port");
    check_json_rejected<NetworkVideo>({{"ttl", 128}}, "out_of_range", "ttl");
    check_json_rejected<NetworkVideo>({{"stream_type", "vp9"}}, "bad_request", "stream_type");
    check_json_rejected<NetworkVideo>({{"ts_packet_count", 16}}, "out_of_range", "ts_packet_count");
}

TEST_CASE("network_video stream type names", "[orion][packets][config][enum]") {
    check_enum<NetworkVideo, StreamType>(
        NetworkVideo{}, [](NetworkVideo& p) -> StreamType& { return p.stream_type; },
        "/stream_type", {{0, "h264"}, {1, "mjpeg"}, {2, "raw"}, {3, "yuv"}}, 4);
}

// --- OrionCameras ------------------------------------------------------------------------

TEST_CASE("cameras golden bytes decode and re-encode", "[orion][packets][config]") {
    check_packet_listed<Cameras>();
    const auto p = decode_golden<Cameras>(cameras_golden);
    REQUIRE(p.cameras.size() == 2);
    const auto& vis = p.cameras[0];
    CHECK(vis.type == CameraType::visible);
    CHECK(vis.protocol == CameraProtocol::sony);
    CHECK(vis.min_focal_length_mm == Approx(4.3));
    CHECK(vis.max_focal_length_mm == Approx(129.0));
    CHECK(vis.pixel_pitch_mm == Approx(0.00155));
    CHECK(vis.array_width == 1920);
    CHECK(vis.array_height == 1080);
    CHECK(vis.align_min[0] == Approx(-256 * i16_pi));
    CHECK(vis.align_min[1] == Approx(-128 * i16_pi));
    CHECK(vis.align_max[0] == Approx(256 * i16_pi));
    CHECK(vis.align_max[1] == Approx(128 * i16_pi));
    const auto& ir = p.cameras[1];
    CHECK(ir.type == CameraType::lwir);
    CHECK(ir.protocol == CameraProtocol::flir);
    CHECK(ir.min_focal_length_mm == Approx(25.0));
    CHECK(ir.max_focal_length_mm == Approx(50.0));
    CHECK(ir.pixel_pitch_mm == Approx(0.017));
    CHECK(ir.array_width == 640);
    CHECK(ir.array_height == 512);
    CHECK(ir.align_min[0] == Approx(-64 * i16_pi));
    CHECK(ir.align_max[1] == Approx(32 * i16_pi));
    check_extra_bytes_ignored<Cameras>(cameras_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"cameras"});
    REQUIRE(j["cameras"].size() == 2);
    CHECK(keys_of(j["cameras"][0]) ==
          std::set<std::string>{"type", "protocol", "min_focal_length_mm", "max_focal_length_mm",
                                "pixel_pitch_mm", "array_width", "array_height", "align_min",
                                "align_max"});
    CHECK(j["cameras"][0]["type"] == "visible");
    CHECK(j["cameras"][1]["protocol"] == "flir");
    CHECK(j["cameras"][0]["align_max"][0].get<double>() == Approx(256 * i16_pi * deg));
    check_json_round_trip(p);
}

TEST_CASE("cameras: the repeat follows NumCameras", "[orion][packets][config]") {
    check_one_short_fails<Cameras>(cameras_golden, "reserved");
    Cameras none;
    CHECK(bytes_of(encode(none)) == Bytes{0, 0, 0, 0});  // no camera: only the header
    const auto empty = decode_minimum<Cameras>(Bytes{0, 0, 0, 0});
    CHECK(empty.cameras.empty());

    // One camera: 4 + 24 bytes, the first camera of the golden vector.
    Bytes one = head(cameras_golden, 28);
    one[0] = 1;
    const auto d = decode<Cameras>(one);
    REQUIRE(d.ok);
    REQUIRE(d.value.cameras.size() == 1);
    CHECK(d.value.cameras[0].array_width == 1920);
    CHECK(bytes_of(encode(d.value)) == one);

    // A count of two with one camera's bytes is too short.
    Bytes cut = head(cameras_golden, 28);
    const auto bad = decode<Cameras>(cut);
    CHECK_FALSE(bad.ok);
    CHECK_THAT(to_string(bad.error), Contains("'type'"));

    // More than NUM_CAMERAS cannot be encoded or sent.
    Cameras three;
    three.cameras.resize(3);
    Payload out;
    CHECK_FALSE(encode(three, out));
    check_json_rejected<Cameras>(
        {{"cameras", json::array({json::object(), json::object(), json::object()})}},
        "out_of_range", "cameras");
}

TEST_CASE("cameras type and protocol names", "[orion][packets][config][enum]") {
    Cameras one;
    one.cameras.resize(1);
    check_enum<Cameras, CameraType>(
        one, [](Cameras& p) -> CameraType& { return p.cameras.at(0).type; }, "/cameras/0/type",
        {{0, "none"}, {1, "visible"}, {2, "swir"}, {3, "mwir"}, {4, "lwir"}}, 5);
    check_enum<Cameras, CameraProtocol>(
        one, [](Cameras& p) -> CameraProtocol& { return p.cameras.at(0).protocol; },
        "/cameras/0/protocol",
        {{0, "unknown"},
         {1, "flir"},
         {2, "aptina"},
         {3, "zafiro"},
         {4, "hitachi"},
         {5, "bae"},
         {6, "sony"},
         {7, "ktnc"}},
        8);
}

// --- Version packets ---------------------------------------------------------------------

TEST_CASE("clevis and crown version golden bytes", "[orion][packets][version]") {
    check_packet_listed<ClevisVersion>();
    check_packet_listed<CrownVersion>();
    const auto clevis = decode_golden<ClevisVersion>(clevis_version_golden);
    CHECK(clevis.version == "1.2.3");
    CHECK(clevis.part_number == "CLV-100-A");
    CHECK(clevis.on_time_min == 123456u);
    check_extra_bytes_ignored<ClevisVersion>(clevis_version_golden);
    const json j = to_json(clevis);
    CHECK(j == json{{"version", "1.2.3"}, {"part_number", "CLV-100-A"}, {"on_time_min", 123456}});
    check_json_round_trip(clevis);

    const auto crown = decode_golden<CrownVersion>(crown_version_golden);
    CHECK(crown.version == "4.0.1");
    CHECK(crown.part_number == "CRN-300-C");
    CHECK(crown.on_time_min == 10000u);
    check_extra_bytes_ignored<CrownVersion>(crown_version_golden);
    check_json_round_trip(crown);
}

TEST_CASE("payload version has a 24-byte version string", "[orion][packets][version]") {
    check_packet_listed<PayloadVersion>();
    const auto p = decode_golden<PayloadVersion>(payload_version_golden);
    CHECK(p.version == "2.5.0-rc1+build.77");
    CHECK(p.part_number == "PLD-200-B");
    CHECK(p.on_time_min == 7u);
    check_extra_bytes_ignored<PayloadVersion>(payload_version_golden);
    CHECK(keys_of(to_json(p)) == std::set<std::string>{"version", "part_number", "on_time_min"});
    check_json_round_trip(p);
}

TEST_CASE("tracker, retract and lens controller versions", "[orion][packets][version]") {
    check_packet_listed<TrackerVersion>();
    check_packet_listed<RetractVersion>();
    check_packet_listed<LensCtlVersion>();
    const auto tracker = decode_golden<TrackerVersion>(tracker_version_golden);
    CHECK(tracker.version == "7.1");
    CHECK(tracker.part_number == "TRK-9");
    CHECK(to_json(tracker) == json{{"version", "7.1"}, {"part_number", "TRK-9"}});
    check_extra_bytes_ignored<TrackerVersion>(tracker_version_golden);
    check_json_round_trip(tracker);

    const auto retract = decode_golden<RetractVersion>(retract_version_golden);
    CHECK(retract.version == "R1.0");
    CHECK(to_json(retract) == json{{"version", "R1.0"}});
    check_extra_bytes_ignored<RetractVersion>(retract_version_golden);
    check_json_round_trip(retract);

    const auto lens = decode_golden<LensCtlVersion>(lensctl_version_golden);
    CHECK(lens.version == "LC-0.9.12");
    CHECK(to_json(lens) == json{{"version", "LC-0.9.12"}});
    check_extra_bytes_ignored<LensCtlVersion>(lensctl_version_golden);
}

TEST_CASE("version packets length limits", "[orion][packets][version]") {
    check_one_short_fails<ClevisVersion>(clevis_version_golden, "part_number");
    check_one_short_fails<CrownVersion>(crown_version_golden, "part_number");
    check_one_short_fails<PayloadVersion>(payload_version_golden, "part_number");
    check_one_short_fails<TrackerVersion>(tracker_version_golden, "part_number");
    check_one_short_fails<RetractVersion>(retract_version_golden, "version");
    check_one_short_fails<LensCtlVersion>(lensctl_version_golden, "version");

    const auto clevis = decode_minimum<ClevisVersion>(clevis_version_golden);
    CHECK(clevis.part_number == "CLV-100-A");
    CHECK(clevis.on_time_min == 0u);  // ICD default
    CHECK(decode_minimum<CrownVersion>(crown_version_golden).on_time_min == 0u);
    CHECK(decode_minimum<PayloadVersion>(payload_version_golden).on_time_min == 0u);
}

TEST_CASE("version strings fill their fixed width", "[orion][packets][version]") {
    // 15 characters and the terminator fill 16 bytes; longer text is cut to 15.
    CrownVersion v;
    v.version = "0123456789ABCDEFXYZ";
    v.part_number = "P";
    const Bytes out = bytes_of(encode(v));
    REQUIRE(out.size() == CrownVersion::max_length);
    CHECK(head(out, 16) == join({text("0123456789ABCDE", 16)}));
    CHECK(decode<CrownVersion>(out).value.version == "0123456789ABCDE");
    check_json_rejected<CrownVersion>({{"version", "0123456789ABCDEF"}}, "out_of_range", "version");
}

// --- OrionBoard --------------------------------------------------------------------------

TEST_CASE("board golden bytes decode and re-encode", "[orion][packets][version]") {
    check_packet_listed<BoardInfo>();
    const auto p = decode_golden<BoardInfo>(board_golden);
    CHECK(p.board_sn == 1000001u);
    CHECK(p.assembly_sn == 2000002u);
    CHECK(p.config == 0xDEADBEEFu);
    CHECK(p.board == Board::crown);
    CHECK(p.manufacture_year == 24);
    CHECK(p.manufacture_month == 7);
    CHECK(p.manufacture_day == 15);
    CHECK(p.calibration_year == 25);
    CHECK(p.calibration_month == 3);
    CHECK(p.calibration_day == 28);
    check_extra_bytes_ignored<BoardInfo>(board_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"board_sn", "assembly_sn", "config", "board",
                                              "manufacture_year", "manufacture_month",
                                              "manufacture_day", "calibration_year",
                                              "calibration_month", "calibration_day"});
    CHECK(j["board"] == "crown");
    CHECK(j["config"] == 0xDEADBEEFu);
    check_json_round_trip(p);
}

TEST_CASE("board length limits", "[orion][packets][version]") {
    // 19 bytes: the calibration year fits in byte 18, the month does not.
    check_one_short_fails<BoardInfo>(board_golden, "calibration_month");
    CHECK(decode_minimum<BoardInfo>(board_golden).calibration_day == 28);
}

// --- OrionAutopilotData ------------------------------------------------------------------

TEST_CASE("autopilot_data golden bytes decode and re-encode", "[orion][packets][external]") {
    check_packet_listed<AutopilotData>();
    const auto p = decode_golden<AutopilotData>(autopilot_data_golden);
    CHECK(p.is_flying);
    CHECK(p.comm_good);
    CHECK(p.agl == 250);
    check_one_short_fails<AutopilotData>(autopilot_data_golden, "agl");
    check_extra_bytes_ignored<AutopilotData>(autopilot_data_golden);

    const json j = to_json(p);
    CHECK(j == json{{"is_flying", true}, {"comm_good", true}, {"agl", 250}});
    check_json_round_trip(p);

    // Below ground (invalid) is carried as the signed value.
    const auto below = decode<AutopilotData>(Bytes{0, 1, 0xFF, 0xF6});
    REQUIRE(below.ok);
    CHECK(below.value.agl == -10);
}

TEST_CASE("autopilot_data JSON rejects bad input", "[orion][packets][external][json]") {
    check_json_rejected<AutopilotData>({{"is_flying", true}, {"armed", true}}, "bad_request",
                                       "armed");
    check_json_rejected<AutopilotData>({{"is_flying", "yes"}}, "bad_request", "is_flying");
    check_json_rejected<AutopilotData>({{"agl", 40000}}, "out_of_range", "agl");
    check_json_rejected<AutopilotData>({{"agl", 10.5}}, "bad_request", "agl");
}

// --- OrionExtHeadingData -----------------------------------------------------------------

TEST_CASE("ext_heading_data golden bytes decode and re-encode", "[orion][packets][external]") {
    check_packet_listed<ExtHeadingData>();
    const auto p = decode_golden<ExtHeadingData>(ext_heading_data_golden);
    CHECK(p.ext_heading == Approx(8192 * i16_pi));
    CHECK(p.noise == Approx(256 * 2.0 * pi / 65535.0));
    CHECK(p.heading_in_gimbal_axis);
    CHECK(p.heading_from_align);
    CHECK(p.pitch == Approx(-2048 * i16_pi));
    check_extra_bytes_ignored<ExtHeadingData>(ext_heading_data_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"ext_heading", "noise", "heading_in_gimbal_axis",
                                              "heading_from_align", "pitch"});
    CHECK(j["ext_heading"].get<double>() == Approx(8192 * i16_pi * deg));
    CHECK(j["noise"].get<double>() == Approx(256 * 360.0 / 65535.0));
    CHECK(j["pitch"].get<double>() == Approx(-2048 * i16_pi * deg));
    CHECK(j["heading_from_align"] == true);
    check_json_round_trip(p);
}

TEST_CASE("ext_heading_data length limits", "[orion][packets][external]") {
    check_one_short_fails<ExtHeadingData>(ext_heading_data_golden, "noise");
    // The ICD's minimum is 4: the flags default to false and pitch to 0.
    const auto p = decode_minimum<ExtHeadingData>(ext_heading_data_golden);
    CHECK(p.noise == Approx(256 * 2.0 * pi / 65535.0));
    CHECK_FALSE(p.heading_in_gimbal_axis);
    CHECK_FALSE(p.heading_from_align);
    CHECK(p.pitch == 0.0);
    // 6 bytes: the flags are there, pitch is not.
    const auto six = decode<ExtHeadingData>(head(ext_heading_data_golden, 6));
    REQUIRE(six.ok);
    CHECK(six.value.heading_in_gimbal_axis);
    CHECK(six.value.heading_from_align);
    CHECK(six.value.pitch == 0.0);
}

TEST_CASE("ext_heading_data JSON rejects bad input", "[orion][packets][external][json]") {
    check_json_rejected<ExtHeadingData>({{"ext_heading", 10.0}, {"roll", 1.0}}, "bad_request",
                                        "roll");
    check_json_rejected<ExtHeadingData>({{"ext_heading", "north"}}, "bad_request", "ext_heading");
    check_json_rejected<ExtHeadingData>({{"ext_heading", 180.5}}, "out_of_range", "ext_heading");
    check_json_rejected<ExtHeadingData>({{"noise", -1.0}}, "out_of_range", "noise");
    check_json_rejected<ExtHeadingData>({{"heading_from_align", 1}}, "bad_request",
                                        "heading_from_align");
}

// --- OrionRangeData ----------------------------------------------------------------------

TEST_CASE("range_data golden bytes decode and re-encode", "[orion][packets][external]") {
    check_packet_listed<RangeData>();
    const auto p = decode_golden<RangeData>(range_data_golden);
    CHECK(p.range_m == Approx(1234.56));
    CHECK(p.max_age_ms == 500);
    CHECK(p.source == RangeSource::laser);
    check_one_short_fails<RangeData>(range_data_golden, "source");
    check_extra_bytes_ignored<RangeData>(range_data_golden);

    const json j = to_json(p);
    CHECK(keys_of(j) == std::set<std::string>{"range_m", "max_age_ms", "source"});
    CHECK(j["range_m"].get<double>() == Approx(1234.56));
    CHECK(j["source"] == "laser");
    check_json_round_trip(p);

    // The contract's `range` command parameters, straight into the packet.
    RangeData cmd;
    JsonError err;
    REQUIRE(
        from_json(json{{"range_m", 1234.56}, {"max_age_ms", 500}, {"source", "laser"}}, cmd, err));
    CHECK(bytes_of(encode(cmd)) == range_data_golden);
}

TEST_CASE("range_data JSON rejects bad input", "[orion][packets][external][json]") {
    check_json_rejected<RangeData>({{"range_m", 100.0}, {"range", 100.0}}, "bad_request",
                                   "'range'");
    check_json_rejected<RangeData>({{"range_m", "far"}}, "bad_request", "range_m");
    check_json_rejected<RangeData>({{"range_m", -1.0}}, "out_of_range", "range_m");
    check_json_rejected<RangeData>({{"range_m", 42949673.0}}, "out_of_range", "range_m");
    check_json_rejected<RangeData>({{"max_age_ms", 65536}}, "out_of_range", "max_age_ms");
    check_json_rejected<RangeData>({{"source", "radar"}}, "bad_request", "source");
}

// --- frames ------------------------------------------------------------------------------

TEST_CASE("range_data and cameras survive framing and the framer", "[orion][packets][framer]") {
    const auto range = decode_golden<RangeData>(range_data_golden);
    const auto cams = decode_golden<Cameras>(cameras_golden);
    Bytes stream = frame_bytes(RangeData::id, range_data_golden);
    REQUIRE(stream.size() == header_size + 7 + checksum_size);
    CHECK(stream[2] == 214);
    CHECK(stream[3] == 7);
    const Bytes second = to_wire(cams);
    stream.insert(stream.end(), second.begin(), second.end());

    Framer framer;
    const auto frames = framer.push(stream);
    REQUIRE(frames.size() == 2);
    CHECK(framer.stats().dropped_bytes == 0);

    REQUIRE(frames[0].id == RangeData::id);
    const auto r = decode<RangeData>(frames[0].data());
    REQUIRE(r.ok);
    CHECK(r.value.range_m == range.range_m);
    CHECK(r.value.max_age_ms == range.max_age_ms);
    CHECK(r.value.source == range.source);

    REQUIRE(frames[1].id == Cameras::id);
    CHECK(Bytes(frames[1].data().begin(), frames[1].data().end()) == cameras_golden);
    const auto c = decode<Cameras>(frames[1].data());
    REQUIRE(c.ok);
    CHECK(to_json(c.value) == to_json(cams));
}
