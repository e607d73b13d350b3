// MISB ST 0601.19 (UAS Datalink Local Set): the one declaration of every tag, 1..143. Each
// row says the item's name (ST 0601's item name in snake_case), how its value is carried
// (kind), its length, its range and the units it has in JSON (interface contract section 1:
// degrees, metres, m/s, seconds). encode(), decode() and the JSON view in local_set.hpp are
// derived from these rows; docs/video.md prints the same table.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string_view>

namespace gimbal::klv {

// The 16-byte universal key of the UAS Datalink Local Set (ST 0601 section 6.2).
inline constexpr std::array<std::uint8_t, 16> uas_datalink_key = {
    0x06, 0x0E, 0x2B, 0x34, 0x02, 0x0B, 0x01, 0x01, 0x0E, 0x01, 0x03, 0x01, 0x01, 0x00, 0x00, 0x00};

// The ST 0601 edition gimbald writes in tag 65 (uas_datalink_ls_version_number).
inline constexpr std::uint8_t st0601_version = 19;

enum class Kind : std::uint8_t {
    checksum,     // tag 1: uint16, written by the encoder
    time_us,      // uint64 microseconds since 1970-01-01 (MISP time) -> ISO-8601 UTC string
    string,       // UTF-8 text, cut at the first zero byte
    linear,       // ST 0601 integer map: `length` bytes onto [min, max] (see mapping below)
    imapb,        // ST 1201 IMAPB(min, max, length)
    uint,         // unsigned integer as it is
    sint,         // signed integer as it is (two's complement)
    enumeration,  // uint8 naming one of `names`
    flags,        // uint8 bit field, bit i named names[i]
    nibbles,      // 4-bit fields, most significant first, named by `names`
    oid_list,     // series of BER-OID integers -> JSON array
    frame_rate,   // BER-OID numerator and optional denominator (tag 127)
    bit_list,     // bit i (from the last byte's least significant bit) set = id i active
    raw,          // nested local set or pack, kept as hex
};

// Linear maps, as ST 0601 defines them:
//   unsigned: wire 0..2^(8n)-1 onto [min, max]        x = wire * (max - min) / (2^(8n) - 1) + min
//   signed:   wire -(2^(8n-1)-1)..2^(8n-1)-1 onto [-max, max]   x = wire * max / (2^(8n-1) - 1)
// and a signed map with `reserved` keeps -(2^(8n-1)) (0x8000, 0x80000000) for "out of range"
// / "N/A (off-earth)", which decodes to JSON null.
struct TagSpec {
    std::uint32_t tag = 0;
    std::string_view name{};
    Kind kind = Kind::raw;
    std::uint8_t length = 0;      // fixed length, or the length the encoder writes by default
    std::uint8_t max_length = 0;  // variable-length items: 1..max_length; 0 = fixed `length`
    bool is_signed = false;
    bool reserved = false;
    double min = 0;
    double max = 0;
    std::string_view units{};  // JSON units ("" for none)
    double to_json = 1.0;      // JSON value = wire value x to_json (km -> m, us -> s)
    bool multiple = false;     // may appear more than once: JSON holds an array
    std::span<const std::string_view> names{};  // enumeration / flag / nibble names
};

namespace names {
inline constexpr std::array<std::string_view, 3> icing_detected = {
    "detector_off", "no_icing_detected", "icing_detected"};
inline constexpr std::array<std::string_view, 6> generic_flag_data = {
    "laser_range",   // 1 = laser on
    "auto_track",    // 1 = auto-track on
    "ir_polarity",   // 1 = black hot, 0 = white hot
    "icing_status",  // 1 = icing detected
    "slant_range",   // 1 = measured, 0 = calculated
    "image_invalid"};
inline constexpr std::array<std::string_view, 4> weapon_load = {
    "station_number", "substation_number", "weapon_type", "weapon_variant"};
inline constexpr std::array<std::string_view, 2> weapon_fired = {"station_number",
                                                                 "substation_number"};
inline constexpr std::array<std::string_view, 9> sensor_field_of_view_name = {
    "ultranarrow",   "narrow",         "medium",         "wide",           "ultrawide",
    "narrow_medium", "2x_ultranarrow", "4x_ultranarrow", "continuous_zoom"};
inline constexpr std::array<std::string_view, 6> operational_mode = {
    "other", "operational", "training", "exercise", "maintenance", "test"};
inline constexpr std::array<std::string_view, 8> positioning_method_source = {
    "on_board_ins", "gps", "galileo", "qzss", "navic", "glonass", "beidou_1", "beidou_2"};
inline constexpr std::array<std::string_view, 13> platform_status = {
    "active",  "preflight",        "preflight_taxiing", "run_up",        "take_off",
    "ingress", "manual_operation", "automated_orbit",   "transitioning", "egress",
    "landing", "landing_taxiing",  "landed_parked"};
inline constexpr std::array<std::string_view, 7> sensor_control_mode = {
    "off",         "home_position",         "uncontrolled", "manual_control",
    "calibrating", "auto_holding_position", "auto_tracking"};
}  // namespace names

namespace rows {
inline constexpr std::string_view deg = "deg", m = "m", mps = "m/s", s = "s", dps = "deg/s",
                                  mbar = "mbar", pct = "%";

constexpr TagSpec lin_u(std::uint32_t t, std::string_view n, std::uint8_t len, double lo, double hi,
                        std::string_view u) {
    return {
        .tag = t, .name = n, .kind = Kind::linear, .length = len, .min = lo, .max = hi, .units = u};
}
constexpr TagSpec lin_s(std::uint32_t t, std::string_view n, std::uint8_t len, double hi,
                        std::string_view u) {
    return {.tag = t,
            .name = n,
            .kind = Kind::linear,
            .length = len,
            .is_signed = true,
            .reserved = true,
            .min = -hi,
            .max = hi,
            .units = u};
}
constexpr TagSpec imapb(std::uint32_t t, std::string_view n, double lo, double hi, std::uint8_t len,
                        std::string_view u, double to_json = 1.0) {
    return {.tag = t,
            .name = n,
            .kind = Kind::imapb,
            .length = len,
            .max_length = 8,
            .min = lo,
            .max = hi,
            .units = u,
            .to_json = to_json};
}
constexpr TagSpec text(std::uint32_t t, std::string_view n) {
    return {.tag = t, .name = n, .kind = Kind::string, .length = 0, .max_length = 127};
}
constexpr TagSpec stamp(std::uint32_t t, std::string_view n, std::uint8_t max_len = 0) {
    return {.tag = t,
            .name = n,
            .kind = Kind::time_us,
            .length = 8,
            .max_length = max_len,
            .units = "ISO-8601 UTC"};
}
constexpr TagSpec integer(std::uint32_t t, std::string_view n, std::uint8_t len,
                          std::string_view u = {}, std::uint8_t max_len = 0) {
    return {
        .tag = t, .name = n, .kind = Kind::uint, .length = len, .max_length = max_len, .units = u};
}
constexpr TagSpec signed_integer(std::uint32_t t, std::string_view n, std::uint8_t len,
                                 std::string_view u, std::uint8_t max_len = 0,
                                 double to_json = 1.0) {
    return {.tag = t,
            .name = n,
            .kind = Kind::sint,
            .length = len,
            .max_length = max_len,
            .is_signed = true,
            .units = u,
            .to_json = to_json};
}
constexpr TagSpec named(std::uint32_t t, std::string_view n, Kind k, std::uint8_t len,
                        std::span<const std::string_view> labels) {
    return {.tag = t, .name = n, .kind = k, .length = len, .names = labels};
}
constexpr TagSpec raw(std::uint32_t t, std::string_view n, bool multiple = false) {
    return {.tag = t, .name = n, .kind = Kind::raw, .multiple = multiple};
}
constexpr TagSpec list(std::uint32_t t, std::string_view n, Kind k) {
    return {.tag = t, .name = n, .kind = k};
}
}  // namespace rows

// clang-format off
inline constexpr std::array<TagSpec, 143> st0601_tags = [] {
    using namespace rows;
    using K = Kind;
    return std::array<TagSpec, 143>{{
        {.tag = 1, .name = "checksum", .kind = K::checksum, .length = 2},
        stamp(2, "precision_time_stamp"),
        text(3, "mission_id"),
        text(4, "platform_tail_number"),
        lin_u(5, "platform_heading_angle", 2, 0, 360, deg),
        lin_s(6, "platform_pitch_angle", 2, 20, deg),
        lin_s(7, "platform_roll_angle", 2, 50, deg),
        lin_u(8, "platform_true_airspeed", 1, 0, 255, mps),
        lin_u(9, "platform_indicated_airspeed", 1, 0, 255, mps),
        text(10, "platform_designation"),
        text(11, "image_source_sensor"),
        text(12, "image_coordinate_system"),
        lin_s(13, "sensor_latitude", 4, 90, deg),
        lin_s(14, "sensor_longitude", 4, 180, deg),
        lin_u(15, "sensor_true_altitude", 2, -900, 19000, m),
        lin_u(16, "sensor_horizontal_field_of_view", 2, 0, 180, deg),
        lin_u(17, "sensor_vertical_field_of_view", 2, 0, 180, deg),
        lin_u(18, "sensor_relative_azimuth_angle", 4, 0, 360, deg),
        lin_s(19, "sensor_relative_elevation_angle", 4, 180, deg),
        lin_u(20, "sensor_relative_roll_angle", 4, 0, 360, deg),
        lin_u(21, "slant_range", 4, 0, 5000000, m),
        lin_u(22, "target_width", 2, 0, 10000, m),
        lin_s(23, "frame_center_latitude", 4, 90, deg),
        lin_s(24, "frame_center_longitude", 4, 180, deg),
        lin_u(25, "frame_center_elevation", 2, -900, 19000, m),
        lin_s(26, "offset_corner_latitude_point_1", 2, 0.075, deg),
        lin_s(27, "offset_corner_longitude_point_1", 2, 0.075, deg),
        lin_s(28, "offset_corner_latitude_point_2", 2, 0.075, deg),
        lin_s(29, "offset_corner_longitude_point_2", 2, 0.075, deg),
        lin_s(30, "offset_corner_latitude_point_3", 2, 0.075, deg),
        lin_s(31, "offset_corner_longitude_point_3", 2, 0.075, deg),
        lin_s(32, "offset_corner_latitude_point_4", 2, 0.075, deg),
        lin_s(33, "offset_corner_longitude_point_4", 2, 0.075, deg),
        named(34, "icing_detected", K::enumeration, 1, names::icing_detected),
        lin_u(35, "wind_direction", 2, 0, 360, deg),
        lin_u(36, "wind_speed", 1, 0, 100, mps),
        lin_u(37, "static_pressure", 2, 0, 5000, mbar),
        lin_u(38, "density_altitude", 2, -900, 19000, m),
        signed_integer(39, "outside_air_temperature", 1, "degC"),
        lin_s(40, "target_location_latitude", 4, 90, deg),
        lin_s(41, "target_location_longitude", 4, 180, deg),
        lin_u(42, "target_location_elevation", 2, -900, 19000, m),
        lin_u(43, "target_track_gate_width", 1, 0, 510, "px"),
        lin_u(44, "target_track_gate_height", 1, 0, 510, "px"),
        lin_u(45, "target_error_estimate_ce90", 2, 0, 4095, m),
        lin_u(46, "target_error_estimate_le90", 2, 0, 4095, m),
        named(47, "generic_flag_data", K::flags, 1, names::generic_flag_data),
        raw(48, "security_local_set"),
        lin_u(49, "differential_pressure", 2, 0, 5000, mbar),
        lin_s(50, "platform_angle_of_attack", 2, 20, deg),
        lin_s(51, "platform_vertical_speed", 2, 180, mps),
        lin_s(52, "platform_sideslip_angle", 2, 20, deg),
        lin_u(53, "airfield_barometric_pressure", 2, 0, 5000, mbar),
        lin_u(54, "airfield_elevation", 2, -900, 19000, m),
        lin_u(55, "relative_humidity", 1, 0, 100, pct),
        lin_u(56, "platform_ground_speed", 1, 0, 255, mps),
        lin_u(57, "ground_range", 4, 0, 5000000, m),
        lin_u(58, "platform_fuel_remaining", 2, 0, 10000, "kg"),
        text(59, "platform_call_sign"),
        named(60, "weapon_load", K::nibbles, 2, names::weapon_load),
        named(61, "weapon_fired", K::nibbles, 1, names::weapon_fired),
        integer(62, "laser_prf_code", 2),
        named(63, "sensor_field_of_view_name", K::enumeration, 1, names::sensor_field_of_view_name),
        lin_u(64, "platform_magnetic_heading", 2, 0, 360, deg),
        integer(65, "uas_datalink_ls_version_number", 1),
        raw(66, "target_location_covariance_matrix"),  // deprecated by ST 0601
        lin_s(67, "alternate_platform_latitude", 4, 90, deg),
        lin_s(68, "alternate_platform_longitude", 4, 180, deg),
        lin_u(69, "alternate_platform_altitude", 2, -900, 19000, m),
        text(70, "alternate_platform_name"),
        lin_u(71, "alternate_platform_heading", 2, 0, 360, deg),
        stamp(72, "event_start_time_utc"),
        raw(73, "rvt_local_set"),
        raw(74, "vmti_local_set"),
        lin_u(75, "sensor_ellipsoid_height", 2, -900, 19000, m),
        lin_u(76, "alternate_platform_ellipsoid_height", 2, -900, 19000, m),
        named(77, "operational_mode", K::enumeration, 1, names::operational_mode),
        lin_u(78, "frame_center_height_above_ellipsoid", 2, -900, 19000, m),
        lin_s(79, "sensor_north_velocity", 2, 327, mps),
        lin_s(80, "sensor_east_velocity", 2, 327, mps),
        raw(81, "image_horizon_pixel_pack"),
        lin_s(82, "corner_latitude_point_1_full", 4, 90, deg),
        lin_s(83, "corner_longitude_point_1_full", 4, 180, deg),
        lin_s(84, "corner_latitude_point_2_full", 4, 90, deg),
        lin_s(85, "corner_longitude_point_2_full", 4, 180, deg),
        lin_s(86, "corner_latitude_point_3_full", 4, 90, deg),
        lin_s(87, "corner_longitude_point_3_full", 4, 180, deg),
        lin_s(88, "corner_latitude_point_4_full", 4, 90, deg),
        lin_s(89, "corner_longitude_point_4_full", 4, 180, deg),
        lin_s(90, "platform_pitch_angle_full", 4, 90, deg),
        lin_s(91, "platform_roll_angle_full", 4, 90, deg),
        lin_s(92, "platform_angle_of_attack_full", 4, 90, deg),
        lin_s(93, "platform_sideslip_angle_full", 4, 180, deg),
        raw(94, "miis_core_identifier"),
        raw(95, "sar_motion_imagery_local_set"),
        imapb(96, "target_width_extended", 0, 1500000, 3, m),
        raw(97, "range_image_local_set"),
        raw(98, "geo_registration_local_set"),
        raw(99, "composite_imaging_local_set"),
        raw(100, "segment_local_set", true),
        raw(101, "amend_local_set", true),
        raw(102, "sdcc_flp", true),
        imapb(103, "density_altitude_extended", -900, 40000, 3, m),
        imapb(104, "sensor_ellipsoid_height_extended", -900, 40000, 3, m),
        imapb(105, "alternate_platform_ellipsoid_height_extended", -900, 40000, 3, m),
        text(106, "stream_designator"),
        text(107, "operational_base"),
        text(108, "broadcast_source"),
        imapb(109, "range_to_recovery_location", 0, 21000, 3, m, 1000.0),  // wire: km
        integer(110, "time_airborne", 4, s, 4),
        integer(111, "propulsion_unit_speed", 4, "rpm", 4),
        imapb(112, "platform_course_angle", 0, 360, 2, deg),
        imapb(113, "altitude_above_ground_level", -900, 40000, 3, m),
        imapb(114, "radar_altimeter", -900, 40000, 3, m),
        raw(115, "control_command", true),
        list(116, "control_command_verification_list", K::oid_list),
        imapb(117, "sensor_azimuth_rate", -1000, 1000, 3, dps),
        imapb(118, "sensor_elevation_rate", -1000, 1000, 3, dps),
        imapb(119, "sensor_roll_rate", -1000, 1000, 3, dps),
        imapb(120, "on_board_mi_storage_percent_full", 0, 100, 2, pct),
        list(121, "active_wavelength_list", K::oid_list),
        raw(122, "country_codes"),
        integer(123, "number_of_navsats_in_view", 1),
        named(124, "positioning_method_source", K::flags, 1, names::positioning_method_source),
        named(125, "platform_status", K::enumeration, 1, names::platform_status),
        named(126, "sensor_control_mode", K::enumeration, 1, names::sensor_control_mode),
        list(127, "sensor_frame_rate_pack", K::frame_rate),
        raw(128, "wavelengths_list"),
        text(129, "target_id"),
        raw(130, "airbase_locations"),
        stamp(131, "take_off_time", 8),
        imapb(132, "transmission_frequency", 1, 99999, 3, "MHz"),
        integer(133, "on_board_mi_storage_capacity", 4, "GB", 4),
        imapb(134, "zoom_percentage", 0, 100, 2, pct),
        text(135, "communications_method"),
        signed_integer(136, "leap_seconds", 4, s, 4),
        signed_integer(137, "correction_offset", 8, s, 8, 1e-6),  // wire: microseconds
        raw(138, "payload_list"),
        list(139, "active_payloads", K::bit_list),
        raw(140, "weapons_stores"),
        raw(141, "waypoint_list"),
        raw(142, "view_domain"),
        raw(143, "metadata_substream_id_pack"),
    }};
}();
// clang-format on

// The row of `tag`, or nullptr for a tag ST 0601.19 does not define.
constexpr const TagSpec* find_tag(std::uint32_t tag) {
    if (tag == 0 || tag > st0601_tags.size()) return nullptr;
    return &st0601_tags[tag - 1];
}

constexpr const TagSpec* find_tag(std::string_view name) {
    for (const auto& row : st0601_tags)
        if (row.name == name) return &row;
    return nullptr;
}

// A tag number by its name, checked at compile time: `constexpr auto t = tag_of("slant_range")`
// does not compile when the name is not in the table.
consteval std::uint32_t tag_of(std::string_view name) {
    const TagSpec* row = find_tag(name);
    if (row == nullptr) throw std::logic_error("not an ST 0601 item name");
    return row->tag;
}

}  // namespace gimbal::klv
