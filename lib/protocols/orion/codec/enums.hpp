// Global enumerations of the OrionPublic ICD ("Enumerations"), with their JSON names:
// lower-case snake case of the ICD name without its prefix (ORION_MODE_GEOPOINT -> "geopoint").
// Enumerations local to one packet live beside that packet.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "protocols/orion/codec/fields.hpp"

namespace gimbal::orion {

// OrionPktType_t
namespace pkt {
inline constexpr std::uint8_t initialize = 0;
inline constexpr std::uint8_t cmd = 1;
inline constexpr std::uint8_t uart_config = 2;
inline constexpr std::uint8_t laser_cmd = 3;
inline constexpr std::uint8_t reset = 4;
inline constexpr std::uint8_t laser_states = 6;
inline constexpr std::uint8_t startup_cmd = 7;
inline constexpr std::uint8_t limits = 34;
inline constexpr std::uint8_t clevis_version = 37;
inline constexpr std::uint8_t reset_source = 38;
inline constexpr std::uint8_t board = 39;
inline constexpr std::uint8_t crown_version = 40;
inline constexpr std::uint8_t payload_version = 41;
inline constexpr std::uint8_t tracker_version = 44;
inline constexpr std::uint8_t diagnostics = 65;
inline constexpr std::uint8_t faults = 66;
inline constexpr std::uint8_t performance = 67;
inline constexpr std::uint8_t software_diagnostics = 68;
inline constexpr std::uint8_t vibration = 69;
inline constexpr std::uint8_t network_diagnostics = 70;
inline constexpr std::uint8_t camera_switch = 96;
inline constexpr std::uint8_t camera_state = 97;
inline constexpr std::uint8_t network_video = 98;
inline constexpr std::uint8_t cameras = 99;
inline constexpr std::uint8_t flir_settings = 103;
inline constexpr std::uint8_t aptina_settings = 104;
inline constexpr std::uint8_t zafiro_settings = 105;
inline constexpr std::uint8_t hitachi_settings = 106;
inline constexpr std::uint8_t bae_settings = 107;
inline constexpr std::uint8_t sony_settings = 108;
inline constexpr std::uint8_t ktnc_settings = 109;
inline constexpr std::uint8_t autopilot_data = 128;
inline constexpr std::uint8_t retract_cmd = 160;
inline constexpr std::uint8_t retract_status = 161;
inline constexpr std::uint8_t debug_string = 177;
inline constexpr std::uint8_t user_data = 178;
inline constexpr std::uint8_t klv_user_data = 179;
inline constexpr std::uint8_t gps_data = 209;
inline constexpr std::uint8_t ext_heading_data = 210;
inline constexpr std::uint8_t ins_quality = 211;
inline constexpr std::uint8_t geolocate_telemetry = 212;
inline constexpr std::uint8_t geopoint_cmd = 213;
inline constexpr std::uint8_t range_data = 214;
inline constexpr std::uint8_t path = 215;
inline constexpr std::uint8_t ins_options = 216;
inline constexpr std::uint8_t stare_start = 217;
inline constexpr std::uint8_t stare_ack = 218;
inline constexpr std::uint8_t network_settings = 228;
inline constexpr std::uint8_t retract_version = 248;
inline constexpr std::uint8_t lensctl_version = 249;
}  // namespace pkt

// GimbalAxis_t, Axis_t, BodyAxis_t, Stator_t: array sizes.
inline constexpr std::size_t num_gimbal_axes = 2;
inline constexpr std::size_t num_axes = 3;
inline constexpr std::size_t num_xyz = 3;
inline constexpr std::size_t num_stators = 3;
inline constexpr std::size_t max_lasers = 2;  // OrionMaxLasers_t
inline constexpr std::size_t max_path_points = 15;

enum class Board : std::uint8_t {  // OrionBoardEnumeration_t
    none = 0,
    clevis = 1,
    crown = 2,
    payload = 3,
    lensctrl = 4,
    misscomp = 5,
};
constexpr std::array<EnumName<Board>, 6> board_names{{{Board::none, "none"},
                                                      {Board::clevis, "clevis"},
                                                      {Board::crown, "crown"},
                                                      {Board::payload, "payload"},
                                                      {Board::lensctrl, "lensctrl"},
                                                      {Board::misscomp, "misscomp"}}};
constexpr std::span<const EnumName<Board>> enum_names(Board) {
    return board_names;
}

enum class Mode : std::uint8_t {  // OrionMode_t
    disabled = 0,
    fault = 1,
    rate = 16,
    geo_rate = 17,
    ffc_auto = 32,
    ffc_manual = 33,
    scene = 48,
    track = 49,
    calibration = 64,
    position = 80,
    position_no_limits = 81,
    geopoint = 96,
    path = 112,
    down = 113,
    unknown = 255,
};
constexpr std::array<EnumName<Mode>, 16> mode_names{{
    {Mode::disabled, "disabled"},
    {Mode::fault, "fault"},
    {Mode::rate, "rate"},
    {Mode::geo_rate, "geo_rate"},
    {Mode::ffc_auto, "ffc_auto"},
    {Mode::ffc_manual, "ffc_manual"},
    {Mode::scene, "scene"},
    {Mode::track, "track"},
    {Mode::calibration, "calibration"},
    {Mode::position, "position"},
    {Mode::position_no_limits, "position_no_limits"},
    {Mode::geopoint, "geopoint"},
    {Mode::path, "path"},
    {Mode::down, "down"},
    {Mode::unknown, "unknown"},
    {Mode::ffc_auto, "ffc"},  // ORION_MODE_FFC: legacy alias of ffc_auto
}};
constexpr std::span<const EnumName<Mode>> enum_names(Mode) {
    return mode_names;
}

enum class LaserType : std::uint8_t {  // OrionLaserType_t
    none = 0,
    pointer = 1,
    marker_10mj = 2,
    lightware = 3,
    jenoptik_dlem = 4,
    vectronix = 5,
};
constexpr std::array<EnumName<LaserType>, 6> laser_type_names{{
    {LaserType::none, "none"},
    {LaserType::pointer, "pointer"},
    {LaserType::marker_10mj, "10mj_marker"},
    {LaserType::lightware, "lightware"},
    {LaserType::jenoptik_dlem, "jenoptik_dlem"},
    {LaserType::vectronix, "vectronix"},
}};
constexpr std::span<const EnumName<LaserType>> enum_names(LaserType) {
    return laser_type_names;
}

enum class RangeSource : std::uint8_t {  // RangeDataSrc_t
    none = 0,
    skylink = 1,
    laser = 2,
    other = 3,
    internal = 4,
    internal_dted = 5,
};
constexpr std::array<EnumName<RangeSource>, 6> range_source_names{{
    {RangeSource::none, "none"},
    {RangeSource::skylink, "skylink"},
    {RangeSource::laser, "laser"},
    {RangeSource::other, "other"},
    {RangeSource::internal, "internal"},
    {RangeSource::internal_dted, "internal_dted"},
}};
constexpr std::span<const EnumName<RangeSource>> enum_names(RangeSource) {
    return range_source_names;
}

enum class RetractCmd : std::uint8_t {  // OrionRetractCmd_t
    disable = 0,
    deploy = 1,
    retract = 2,
};
constexpr std::array<EnumName<RetractCmd>, 3> retract_cmd_names{{
    {RetractCmd::disable, "disable"},
    {RetractCmd::deploy, "deploy"},
    {RetractCmd::retract, "retract"},
}};
constexpr std::span<const EnumName<RetractCmd>> enum_names(RetractCmd) {
    return retract_cmd_names;
}

enum class UserDataPort : std::uint8_t {  // UserDataPort_t
    ethernet = 0,
    primary = 2,
    fp2 = 3,
    fp1 = 4,
    fp3 = 8,
    fp4 = 9,
    current = 255,
};
constexpr std::array<EnumName<UserDataPort>, 7> user_data_port_names{{
    {UserDataPort::ethernet, "ethernet"},
    {UserDataPort::primary, "primary"},
    {UserDataPort::fp2, "fp2"},
    {UserDataPort::fp1, "fp1"},
    {UserDataPort::fp3, "fp3"},
    {UserDataPort::fp4, "fp4"},
    {UserDataPort::current, "current"},
}};
constexpr std::span<const EnumName<UserDataPort>> enum_names(UserDataPort) {
    return user_data_port_names;
}

}  // namespace gimbal::orion
