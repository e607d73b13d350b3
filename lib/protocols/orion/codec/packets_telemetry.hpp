// ICD section "Packets sent regularly by the gimbal".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/fields.hpp"

namespace gimbal::orion {

// --- GeolocateTelemetryCore ------------------------------------------------------------------

enum class InsRotation : std::uint8_t { gimbal_native = 0, platform = 1, payload_ball = 2 };
constexpr std::array<EnumName<InsRotation>, 3> ins_rotation_names{{
    {InsRotation::gimbal_native, "in_gimbal_native"},
    {InsRotation::platform, "in_platform"},
    {InsRotation::payload_ball, "in_payload_ball"},
}};
constexpr std::span<const EnumName<InsRotation>> enum_names(InsRotation) {
    return ins_rotation_names;
}

// GeolocateTelemetryCore (212), 10 Hz: where the gimbal is and where it looks.
struct GeolocateTelemetry {
    static constexpr std::uint8_t id = pkt::geolocate_telemetry;
    static constexpr std::string_view name = "geolocate_telemetry";
    static constexpr std::size_t min_length = 46;
    static constexpr std::size_t max_length = 89;

    std::uint32_t system_time_ms = 0;
    std::uint32_t gps_itow_ms = 0;
    std::uint16_t gps_week = 0;
    double geoid_undulation = 0;  // m
    double lat = 0;               // rad
    double lon = 0;               // rad
    double alt = 0;               // m above WGS84
    std::array<double, 3> vel_ned{};
    std::array<double, 4> quat{};      // gimbal mount -> NED, [w x y z]
    double pan = 0;                    // rad
    double tilt = 0;                   // rad
    double hfov = 0;                   // rad
    double vfov = 0;                   // rad
    std::array<double, 3> los_ecef{};  // m
    std::uint16_t pixel_width = 0;
    std::uint16_t pixel_height = 0;
    Mode mode = Mode::unknown;
    double path_progress = 0;
    double stare_time_s = 0;
    std::uint8_t path_from = 0;
    std::uint8_t path_to = 0;
    std::array<double, 2> image_shifts{};  // rad
    double image_shift_delta_time_s = 0;
    double image_shift_confidence = 0;
    std::array<double, 2> output_shifts{};  // rad
    RangeSource range_source = RangeSource::skylink;
    std::uint8_t leap_seconds = 18;
    double pan_alignment = 0;   // rad
    double tilt_alignment = 0;  // rad
    InsRotation ins_rotation_option = InsRotation::gimbal_native;
    std::array<double, 4> ins_quat{};

    template <class V>
    void fields(V& v) {
        v.field("system_time_ms", system_time_ms, u32);
        v.field("gps_itow_ms", gps_itow_ms, u32);
        v.field("gps_week", gps_week, u16);
        v.field("geoid_undulation", geoid_undulation, i16, 32767.0 / 120.0);
        v.field("lat", lat, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("lon", lon, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("alt", alt, i32, 10000.0);
        v.field("vel_ned", vel_ned, i16, 100.0);
        v.field("quat", quat, i16, 32767.0);
        v.field("pan", pan, i16, 32767.0 / pi, Unit::radians);
        v.field("tilt", tilt, i16, 32767.0 / pi, Unit::radians);
        v.field("hfov", hfov, u16, 65535.0 / (2.0 * pi), Unit::radians);
        v.field("vfov", vfov, u16, 65535.0 / (2.0 * pi), Unit::radians);
        v.optional();
        v.field("los_ecef", los_ecef, i16, 1.0);
        v.field("pixel_width", pixel_width, u16);
        v.field("pixel_height", pixel_height, u16);
        v.field("mode", mode, u8);
        v.field("path_progress", path_progress, u8, 255.0);
        v.field("stare_time_s", stare_time_s, u8, 255.0 / 2.55);
        v.field("path_from", path_from, u8);
        v.field("path_to", path_to, u8);
        v.field("image_shifts", image_shifts, i32, 1000000.0, Unit::radians);
        v.field("image_shift_delta_time_s", image_shift_delta_time_s, u16, 1000.0);
        v.field("image_shift_confidence", image_shift_confidence, u8, 255.0);
        v.field("output_shifts", output_shifts, i16, 32767.0 / pi, Unit::radians);
        v.field("range_source", range_source, u8);
        v.field("leap_seconds", leap_seconds, u8);
        v.field("pan_alignment", pan_alignment, i8, 1000.0, Unit::radians);
        v.field("tilt_alignment", tilt_alignment, i8, 1000.0, Unit::radians);
        v.field("ins_rotation_option", ins_rotation_option, u8);
        if (ins_rotation_option != InsRotation::gimbal_native)
            v.field("ins_quat", ins_quat, i16, 32767.0);
    }
};

// --- OrionPerformance --------------------------------------------------------------------------

// OrionPerformance (67), 4 Hz: stabilization errors and motor current per gimbal axis.
struct Performance {
    static constexpr std::uint8_t id = pkt::performance;
    static constexpr std::string_view name = "performance";
    static constexpr std::size_t min_length = 20;
    static constexpr std::size_t max_length = 20;

    std::array<double, num_gimbal_axes> rms_quad{};
    std::array<double, num_gimbal_axes> rms_dir{};
    std::array<double, num_gimbal_axes> rms_vel{};
    std::array<double, num_gimbal_axes> rms_pos{};
    std::array<double, num_gimbal_axes> iout{};  // A

    template <class V>
    void fields(V& v) {
        v.field("rms_quad", rms_quad, u16, 1000000.0);
        v.field("rms_dir", rms_dir, u16, 1000000.0);
        v.field("rms_vel", rms_vel, u16, 1000.0);
        v.field("rms_pos", rms_pos, u16, 1000000.0);
        v.field("iout", iout, u16, 1000.0);
    }
};

// --- OrionDiagnostics --------------------------------------------------------------------------

// OrionDiagnostics (65), every 3 s: power rails and board temperatures.
struct Diagnostics {
    static constexpr std::uint8_t id = pkt::diagnostics;
    static constexpr std::string_view name = "diagnostics";
    static constexpr std::size_t min_length = 28;
    static constexpr std::size_t max_length = 28;

    double voltage24 = 0;   // V
    double voltage12 = 0;   // V
    double voltage3v3 = 0;  // V
    double current24 = 0;   // A
    double current12 = 0;   // A
    double current3v3 = 0;  // A
    double crown_temp = 0;  // deg C
    double sla_temp = 0;    // deg C
    double gyro_temp = 0;   // deg C
    double voltage24_var = 0;
    double voltage12_var = 0;
    double voltage3v3_var = 0;
    double current24_var = 0;
    double current12_var = 0;
    double current3v3_var = 0;

    template <class V>
    void fields(V& v) {
        v.field("voltage24", voltage24, u16, 1000.0);
        v.field("voltage12", voltage12, u16, 1000.0);
        v.field("voltage3v3", voltage3v3, u16, 1000.0);
        v.field("current24", current24, u16, 1000.0);
        v.field("current12", current12, u16, 1000.0);
        v.field("current3v3", current3v3, u16, 1000.0);
        v.field("crown_temp", crown_temp, i8, 1.0);
        v.field("sla_temp", sla_temp, i8, 1.0);
        v.field("gyro_temp", gyro_temp, i8, 1.0);
        v.reserved(u8);
        v.field("voltage24_var", voltage24_var, u16, 100000.0);
        v.field("voltage12_var", voltage12_var, u16, 100000.0);
        v.field("voltage3v3_var", voltage3v3_var, u16, 100000.0);
        v.field("current24_var", current24_var, u16, 100000.0);
        v.field("current12_var", current12_var, u16, 100000.0);
        v.field("current3v3_var", current3v3_var, u16, 100000.0);
    }
};

// --- OrionSoftwareDiagnostics --------------------------------------------------------------------

inline constexpr std::size_t max_software_cores = 2;
inline constexpr std::size_t max_software_threads = 10;

struct ThreadLoading {
    double cpu_load = 0;       // %
    double heap_load = 0;      // %
    double stack_load = 0;     // %
    double watchdog_left = 0;  // %
    double num_iterations = 0;
    double worstcase = 0;  // ratio to the average run time

    template <class V>
    void fields(V& v) {
        v.field("cpu_load", cpu_load, u8, 255.0 / 100.0);
        v.field("heap_load", heap_load, u8, 255.0 / 100.0);
        v.field("stack_load", stack_load, u8, 255.0 / 100.0);
        v.field("watchdog_left", watchdog_left, u8, 255.0 / 100.0);
        v.field("num_iterations", num_iterations, u8, 0.1);
        v.field("worstcase", worstcase, u8, 255.0 / 25.5);
    }
};

struct CoreLoading {
    double cpu_load = 0;    // %
    double heap_load = 0;   // %
    double stack_load = 0;  // %
    std::vector<ThreadLoading> threads;

    template <class V>
    void fields(V& v) {
        v.field("cpu_load", cpu_load, u8, 255.0 / 100.0);
        v.field("heap_load", heap_load, u8, 255.0 / 100.0);
        v.field("stack_load", stack_load, u8, 255.0 / 100.0);
        v.reserved(u8);
        v.count("num_threads", threads, u8, max_software_threads);
        v.group("threads", threads);
    }
};

// OrionSoftwareDiagnostics (68), 1 Hz per board: CPU, heap and stack load per core and thread.
struct SoftwareDiagnostics {
    static constexpr std::uint8_t id = pkt::software_diagnostics;
    static constexpr std::string_view name = "software_diagnostics";
    static constexpr std::size_t min_length = 4;
    static constexpr std::size_t max_length = 134;

    Board source_board = Board::none;
    std::vector<CoreLoading> cores;

    template <class V>
    void fields(V& v) {
        v.field("source_board", source_board, u8);
        v.count("num_cores", cores, u8, max_software_cores);  // the repeat starts after reserved
        v.reserved(u16);
        v.group("cores", cores);
    }
};

// --- OrionVibration ----------------------------------------------------------------------------

inline constexpr std::size_t num_fft_points = 16;

struct FftPoint {
    double frequency = 0;                  // Hz
    std::array<double, num_axes> accel{};  // fraction of max_accel
    std::array<double, num_axes> gyro{};   // fraction of max_gyro

    template <class V>
    void fields(V& v) {
        v.field("frequency", frequency, u16, 65535.0 / 200.0);
        v.field("accel", accel, u8, 255.0);
        v.field("gyro", gyro, u8, 255.0);
    }
};

// OrionVibration (69), every 5 s: platform vibration spectrum.
// FftData is a fixed repeat of 16 structures. The vocabulary has group() only for counted
// repeats, so fft_data is a vector that must always hold num_fft_points items; from_json cannot
// read "fft_data" (no count sets its maximum).
struct Vibration {
    static constexpr std::uint8_t id = pkt::vibration;
    static constexpr std::string_view name = "vibration";
    static constexpr std::size_t min_length = 140;
    static constexpr std::size_t max_length = 140;

    std::array<double, num_axes> max_accel{};  // m/s/s
    std::array<double, num_axes> max_gyro{};   // rad/s
    std::vector<FftPoint> fft_data = std::vector<FftPoint>(num_fft_points);

    template <class V>
    void fields(V& v) {
        v.field("max_accel", max_accel, i16, 32767.0 / 20.0);
        v.field("max_gyro", max_gyro, i16, 32767.0 / 0.1, Unit::radians);
        v.group("fft_data", fft_data);
    }
};

// --- NetworkDiagnostics ------------------------------------------------------------------------

// NetworkDiagnostics (70): Ethernet interface counters.
struct NetworkDiagnostics {
    static constexpr std::uint8_t id = pkt::network_diagnostics;
    static constexpr std::string_view name = "network_diagnostics";
    static constexpr std::size_t min_length = 36;
    static constexpr std::size_t max_length = 36;

    std::uint16_t flags = 0;
    std::uint32_t rx_bytes = 0;
    std::uint32_t tx_bytes = 0;
    std::uint32_t rx_packets = 0;
    std::uint32_t tx_packets = 0;
    std::uint16_t rx_errors = 0;
    std::uint16_t tx_errors = 0;
    std::uint16_t rx_drops = 0;
    std::uint16_t tx_drops = 0;
    std::uint16_t rx_fifo_errors = 0;
    std::uint16_t tx_fifo_errors = 0;
    std::uint16_t frame_errors = 0;
    std::uint16_t collisions = 0;
    std::uint16_t carrier_errors = 0;

    template <class V>
    void fields(V& v) {
        v.field("flags", flags, u16);
        v.field("rx_bytes", rx_bytes, u32);
        v.field("tx_bytes", tx_bytes, u32);
        v.field("rx_packets", rx_packets, u32);
        v.field("tx_packets", tx_packets, u32);
        v.field("rx_errors", rx_errors, u16);
        v.field("tx_errors", tx_errors, u16);
        v.field("rx_drops", rx_drops, u16);
        v.field("tx_drops", tx_drops, u16);
        v.field("rx_fifo_errors", rx_fifo_errors, u16);
        v.field("tx_fifo_errors", tx_fifo_errors, u16);
        v.field("frame_errors", frame_errors, u16);
        v.field("collisions", collisions, u16);
        v.field("carrier_errors", carrier_errors, u16);
    }
};

// --- OrionRetractStatus ------------------------------------------------------------------------

enum class RetractState : std::uint8_t {  // OrionRetractState_t
    disabled = 0,
    retracted = 1,
    retracting = 2,
    deploying = 3,
    deployed = 4,
    fault = 5,
};
constexpr std::array<EnumName<RetractState>, 6> retract_state_names{{
    {RetractState::disabled, "disabled"},
    {RetractState::retracted, "retracted"},
    {RetractState::retracting, "retracting"},
    {RetractState::deploying, "deploying"},
    {RetractState::deployed, "deployed"},
    {RetractState::fault, "fault"},
}};
constexpr std::span<const EnumName<RetractState>> enum_names(RetractState) {
    return retract_state_names;
}

// OrionRetractStatus (161): sent regularly only when a retract mechanism is installed.
struct RetractStatus {
    static constexpr std::uint8_t id = pkt::retract_status;
    static constexpr std::string_view name = "retract_status";
    static constexpr std::size_t min_length = 6;
    static constexpr std::size_t max_length = 6;

    RetractCmd cmd = RetractCmd::disable;
    RetractState state = RetractState::disabled;
    double pos = 0;  // rad
    std::uint16_t flags = 0;

    template <class V>
    void fields(V& v) {
        v.field("cmd", cmd, u8);
        v.field("state", state, u8);
        v.field("pos", pos, i16, 1000.0, Unit::radians);
        v.field("flags", flags, u16);
    }
};

// --- StareStart --------------------------------------------------------------------------------

// StareStart (217): a step-stare image should be taken now; answer with StareAck.
struct StareStart {
    static constexpr std::uint8_t id = pkt::stare_start;
    static constexpr std::string_view name = "stare_start";
    static constexpr std::size_t min_length = 20;
    static constexpr std::size_t max_length = 52;

    std::uint32_t system_time_ms = 0;
    double max_stare_time_s = 0;
    bool along_track_stare = false;
    bool prev_stare_terminated_by_time = false;
    bool stare_started_by_time = false;
    bool gimbal_data_valid = false;
    bool stare_reset = false;
    double prev_stare_time_s = 0;
    double stare_load = 0;  // ratio, 0..1
    double lat = 0;         // rad, desired stare point
    double lon = 0;         // rad
    double alt = 0;         // m above WGS84
    double gimbal_lat = 0;  // rad
    double gimbal_lon = 0;  // rad
    double gimbal_alt = 0;  // m above WGS84
    std::array<double, 4> gimbal_quat{};
    double pan = 0;   // rad
    double tilt = 0;  // rad
    RangeSource range_source = RangeSource::none;
    double slant_range = 0;        // m
    double along_stare_angle = 0;  // rad
    double cross_stare_angle = 0;  // rad

    template <class V>
    void fields(V& v) {
        v.field("system_time_ms", system_time_ms, u32);
        v.field("max_stare_time_s", max_stare_time_s, u8, 255.0 / 2.55);
        v.bits("along_track_stare", along_track_stare, 1);
        v.bits("prev_stare_terminated_by_time", prev_stare_terminated_by_time, 1);
        v.bits("stare_started_by_time", stare_started_by_time, 1);
        v.bits("gimbal_data_valid", gimbal_data_valid, 1);
        v.bits("stare_reset", stare_reset, 1);
        // bits 5:2..5:0 are not in the ICD table; the next whole-byte field starts at byte 6
        v.field("prev_stare_time_s", prev_stare_time_s, u8, 255.0 / 2.55);
        v.field("stare_load", stare_load, u8, 255.0);
        v.field("lat", lat, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("lon", lon, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("alt", alt, i32, 10000.0);
        v.optional();
        v.field("gimbal_lat", gimbal_lat, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("gimbal_lon", gimbal_lon, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("gimbal_alt", gimbal_alt, i32, 10000.0);
        v.field("gimbal_quat", gimbal_quat, i16, 32767.0);
        v.field("pan", pan, i16, 32767.0 / pi, Unit::radians);
        v.field("tilt", tilt, i16, 32767.0 / pi, Unit::radians);
        v.field("range_source", range_source, u8);
        v.field("slant_range", slant_range, u24, 100.0);
        v.field("along_stare_angle", along_stare_angle, i16, 32767.0 / pi, Unit::radians);
        v.field("cross_stare_angle", cross_stare_angle, i16, 32767.0 / pi, Unit::radians);
    }
};

// --- OrionResetSource --------------------------------------------------------------------------

// OrionResetSource (38): sent by each processor after it boots.
struct ResetSource {
    static constexpr std::uint8_t id = pkt::reset_source;
    static constexpr std::string_view name = "reset_source";
    static constexpr std::size_t min_length = 8;
    static constexpr std::size_t max_length = 9;

    std::uint32_t vector = 0;   // interrupt vector of the last reset
    std::uint32_t address = 0;  // program counter before the reset
    Board source_board = Board::clevis;

    template <class V>
    void fields(V& v) {
        v.field("vector", vector, u32);
        v.field("address", address, u32);
        v.optional();
        v.field("source_board", source_board, u8);
    }
};

// --- DebugString -------------------------------------------------------------------------------

enum class DebugPriority : std::uint8_t {  // debugPriority
    log = 0,
    info = 1,
    warn = 2,
    error = 3,
    fatal = 4,
};
constexpr std::array<EnumName<DebugPriority>, 5> debug_priority_names{{
    {DebugPriority::log, "log"},
    {DebugPriority::info, "info"},
    {DebugPriority::warn, "warn"},
    {DebugPriority::error, "error"},
    {DebugPriority::fatal, "fatal"},
}};
constexpr std::span<const EnumName<DebugPriority>> enum_names(DebugPriority) {
    return debug_priority_names;
}

inline constexpr std::size_t max_debug_text_bytes = 128;  // including the terminating zero

// DebugString (177): a human readable message from one board. The state model turns it into
// the contract's debug event (source, priority, text = description).
struct DebugString {
    static constexpr std::uint8_t id = pkt::debug_string;
    static constexpr std::string_view name = "debug_string";
    static constexpr std::size_t min_length = 5;
    static constexpr std::size_t max_length = 132;

    Board source = Board::none;
    DebugPriority priority = DebugPriority::log;
    std::string description;

    template <class V>
    void fields(V& v) {
        v.field("source", source, u8);
        v.field("priority", priority, u8);
        v.reserved(u8);
        v.reserved(u8);
        v.string("description", description, max_debug_text_bytes);
    }
};

// --- KlvUserData -------------------------------------------------------------------------------

inline constexpr std::size_t max_klv_value_bytes = 127;

// KlvUserData (179): sets or reports one user-configurable KLV tag.
struct KlvUserData {
    static constexpr std::uint8_t id = pkt::klv_user_data;
    static constexpr std::string_view name = "klv_user_data";
    static constexpr std::size_t min_length = 3;
    static constexpr std::size_t max_length = 130;

    std::uint8_t key = 0;      // UAS Local Set key
    std::uint8_t sub_key = 0;  // sub-key, if applicable
    std::vector<std::uint8_t> value;

    template <class V>
    void fields(V& v) {
        v.field("key", key, u8);
        v.field("sub_key", sub_key, u8);
        v.count("length", value, u8, max_klv_value_bytes);
        v.field("value", value, u8);
    }
};

// --- GpsData -----------------------------------------------------------------------------------

enum class GpsSource : std::uint8_t {  // gpsSource_t
    external = 0,
    ublox = 1,
    mavlink = 2,
    nmea = 3,
    novatel = 4,
    autopilot = 5,
    piksi = 6,
};
// The ICD names carry no prefix, so the JSON names are the whole names in snake case.
constexpr std::array<EnumName<GpsSource>, 8> gps_source_names{{
    {GpsSource::external, "external_source"},
    {GpsSource::ublox, "ublox_source"},
    {GpsSource::mavlink, "mavlink_source"},
    {GpsSource::nmea, "nmea_source"},
    {GpsSource::novatel, "novatel_source"},
    {GpsSource::autopilot, "autopilot_source"},
    {GpsSource::piksi, "piksi_source"},
    {GpsSource::autopilot, "piccolo_source"},  // piccoloSource: kept for backward compatibility
}};
constexpr std::span<const EnumName<GpsSource>> enum_names(GpsSource) {
    return gps_source_names;
}

enum class UbloxFixType : std::uint8_t {  // ubloxFixType_t
    no_fix = 0,
    dead_reckoning_only = 1,
    two_d_fix = 2,
    three_d_fix = 3,
    gnss_dead_reckoning = 4,
    time_only = 5,
};
constexpr std::array<EnumName<UbloxFixType>, 6> ublox_fix_type_names{{
    {UbloxFixType::no_fix, "no_fix"},
    {UbloxFixType::dead_reckoning_only, "dead_reckoning_only"},
    {UbloxFixType::two_d_fix, "two_d_fix"},
    {UbloxFixType::three_d_fix, "three_d_fix"},
    {UbloxFixType::gnss_dead_reckoning, "gnss_dead_reckoning"},
    {UbloxFixType::time_only, "time_only"},
}};
constexpr std::span<const EnumName<UbloxFixType>> enum_names(UbloxFixType) {
    return ublox_fix_type_names;
}

// GpsData (209): raw GPS solution, 1 Hz from the gimbal; a client may send it to override the
// gimbal's own GPS (ideally at 4 Hz).
struct GpsData {
    static constexpr std::uint8_t id = pkt::gps_data;
    static constexpr std::string_view name = "gps_data";
    static constexpr std::size_t min_length = 54;
    static constexpr std::size_t max_length = 69;

    bool multi_ant_heading_valid = false;
    UbloxFixType fix_type = UbloxFixType::no_fix;
    std::uint8_t fix_state = 0;  // uBlox fix state flags
    std::uint8_t tracked_sats = 0;
    double pdop = 0;
    double lat = 0;  // rad
    double lon = 0;  // rad
    double alt = 0;  // m above WGS84
    std::array<double, 3> vel_ned{};
    double hacc = 0;         // m
    double vacc = 0;         // m
    double speed_acc = 0;    // m/s
    double heading_acc = 0;  // rad
    std::uint32_t itow_ms = 0;
    std::uint16_t week = 0;
    double geoid_undulation = 0;  // m
    GpsSource source = GpsSource::external;
    bool detailed_accuracy_valid = false;
    bool vertical_velocity_valid = false;
    std::uint8_t leap_seconds = 17;
    double multi_ant_heading = 0;          // rad
    std::array<double, 3> pos_accuracy{};  // m, NED
    std::array<double, 3> vel_accuracy{};  // m/s, NED

    template <class V>
    void fields(V& v) {
        v.bits("multi_ant_heading_valid", multi_ant_heading_valid, 1);
        v.reserved_bits(3);
        v.bits("fix_type", fix_type, 4);
        v.field("fix_state", fix_state, u8);
        v.field("tracked_sats", tracked_sats, u8);
        v.field("pdop", pdop, u8, 10.0);
        v.field("lat", lat, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("lon", lon, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("alt", alt, i32, 10000.0);
        v.field("vel_ned", vel_ned, i32, 1000.0);
        v.field("hacc", hacc, i32, 1000.0);
        v.field("vacc", vacc, i32, 1000.0);
        v.field("speed_acc", speed_acc, i32, 1000.0);
        v.field("heading_acc", heading_acc, i32, 5729578.0, Unit::radians);
        v.field("itow_ms", itow_ms, u32);
        v.field("week", week, u16);
        v.field("geoid_undulation", geoid_undulation, i16, 100.0);
        v.field("source", source, u8);
        v.reserved_bits(6);
        v.bits("detailed_accuracy_valid", detailed_accuracy_valid, 1);
        v.bits("vertical_velocity_valid", vertical_velocity_valid, 1);
        v.optional();
        v.field("leap_seconds", leap_seconds, u8);
        if (multi_ant_heading_valid)
            v.field("multi_ant_heading", multi_ant_heading, i16, 32767.0 / pi, Unit::radians);
        if (detailed_accuracy_valid) {
            v.field("pos_accuracy", pos_accuracy, u16, 1000.0);
            v.field("vel_accuracy", vel_accuracy, u16, 1000.0);
        }
    }
};

// --- InsQuality --------------------------------------------------------------------------------

enum class InsMode : std::uint8_t {  // insMode_t
    init1 = 0,
    init2 = 1,
    ahrs = 2,
    run_hard = 3,
    run = 4,
    run_tight = 5,
};
constexpr std::array<EnumName<InsMode>, 6> ins_mode_names{{
    {InsMode::init1, "init1"},
    {InsMode::init2, "init2"},
    {InsMode::ahrs, "ahrs"},
    {InsMode::run_hard, "run_hard"},
    {InsMode::run, "run"},
    {InsMode::run_tight, "run_tight"},
}};
constexpr std::span<const EnumName<InsMode>> enum_names(InsMode) {
    return ins_mode_names;
}

enum class ImuType : std::uint8_t {  // imuType_t
    internal = 0,
    sensonor = 1,
    dmu11 = 2,
    external = 3,
    epson = 4,
};
constexpr std::array<EnumName<ImuType>, 5> imu_type_names{{
    {ImuType::internal, "internal"},
    {ImuType::sensonor, "sensonor"},
    {ImuType::dmu11, "dmu11"},
    {ImuType::external, "external"},
    {ImuType::epson, "epson"},
}};
constexpr std::span<const EnumName<ImuType>> enum_names(ImuType) {
    return imu_type_names;
}

// InsQuality (211), 1 Hz: how good the INS solution is. The has_* flags switch on the blocks
// of bias states the INS reports.
struct InsQuality {
    static constexpr std::uint8_t id = pkt::ins_quality;
    static constexpr std::string_view name = "ins_quality";
    static constexpr std::size_t min_length = 34;
    static constexpr std::size_t max_length = 79;

    std::uint32_t system_time_ms = 0;
    GpsSource gps_source = GpsSource::external;
    ImuType imu_type = ImuType::internal;
    InsMode ins_mode = InsMode::init1;
    bool has_gyro_bias = false;
    bool has_gravity_bias = false;
    bool has_accel_bias = false;
    bool has_clock_bias = false;
    bool has_pan_tilt_bias = false;
    bool pos_rejected = false;
    bool vel_rejected = false;
    bool hdg_rejected = false;
    double gps_period_s = 0;
    double hdg_period_s = 0;
    double pos_chi_square = 0;
    double vel_chi_square = 0;
    double hdg_chi_square = 0;
    std::array<double, 3> att_confidence{};    // rad, body roll/pitch/yaw
    std::array<double, 3> vel_confidence{};    // m/s, NED
    std::array<double, 3> pos_confidence{};    // m, NED
    std::array<double, 3> gyro_confidence{};   // rad/s, body roll/pitch/yaw
    std::array<double, 3> accel_confidence{};  // m/s/s, body XYZ
    double gravity_confidence = 0;             // m/s/s
    double clock_bias_confidence = 0;          // m
    double clock_drift_confidence = 0;         // m/s
    std::array<double, 3> gyro_bias{};         // rad/s, body roll/pitch/yaw
    std::array<double, 3> accel_bias{};        // m/s/s, body XYZ
    double gravity_bias = 0;                   // m/s/s
    double clock_bias = 0;                     // m
    double clock_drift = 0;                    // m/s
    std::uint8_t num_tight_sat_pos_updates = 0;
    std::uint8_t num_tight_sat_vel_updates = 0;
    std::uint8_t num_tight_pos_updates = 0;
    std::uint8_t num_tight_vel_updates = 0;
    std::array<double, num_gimbal_axes> pan_tilt_bias{};  // rad
    double pan_tilt_chi_square = 0;

    template <class V>
    void fields(V& v) {
        v.field("system_time_ms", system_time_ms, u32);
        v.field("gps_source", gps_source, u8);
        v.reserved_bits(5);
        v.bits("imu_type", imu_type, 3);
        v.field("ins_mode", ins_mode, u8);
        v.bits("has_gyro_bias", has_gyro_bias, 1);
        v.bits("has_gravity_bias", has_gravity_bias, 1);
        v.bits("has_accel_bias", has_accel_bias, 1);
        v.bits("has_clock_bias", has_clock_bias, 1);
        v.bits("has_pan_tilt_bias", has_pan_tilt_bias, 1);
        v.bits("pos_rejected", pos_rejected, 1);
        v.bits("vel_rejected", vel_rejected, 1);
        v.bits("hdg_rejected", hdg_rejected, 1);
        v.field("gps_period_s", gps_period_s, u8, 100.0);
        v.field("hdg_period_s", hdg_period_s, u8, 100.0);
        v.field("pos_chi_square", pos_chi_square, f16_9);
        v.field("vel_chi_square", vel_chi_square, f16_9);
        v.field("hdg_chi_square", hdg_chi_square, f16_9);
        v.field("att_confidence", att_confidence, u16, 10000.0, Unit::radians);
        v.field("vel_confidence", vel_confidence, u16, 100.0);
        v.field("pos_confidence", pos_confidence, u16, 100.0);
        if (has_gyro_bias)
            v.field("gyro_confidence", gyro_confidence, u16, 100000.0, Unit::radians);
        if (has_accel_bias) v.field("accel_confidence", accel_confidence, u16, 30000.0);
        if (has_gravity_bias) v.field("gravity_confidence", gravity_confidence, u16, 30000.0);
        if (has_clock_bias) {
            v.field("clock_bias_confidence", clock_bias_confidence, u16, 10000.0);
            v.field("clock_drift_confidence", clock_drift_confidence, u16, 10000.0);
        }
        if (has_gyro_bias) v.field("gyro_bias", gyro_bias, i16, 100000.0, Unit::radians);
        if (has_accel_bias) v.field("accel_bias", accel_bias, u16, 30000.0);
        if (has_gravity_bias) v.field("gravity_bias", gravity_bias, u16, 30000.0);
        if (has_clock_bias) {
            v.field("clock_bias", clock_bias, i16, 100.0);
            v.field("clock_drift", clock_drift, i16, 1000.0);
            v.field("num_tight_sat_pos_updates", num_tight_sat_pos_updates, u8);
            v.field("num_tight_sat_vel_updates", num_tight_sat_vel_updates, u8);
            v.field("num_tight_pos_updates", num_tight_pos_updates, u8);
            v.field("num_tight_vel_updates", num_tight_vel_updates, u8);
        }
        if (has_pan_tilt_bias) {
            v.field("pan_tilt_bias", pan_tilt_bias, i16, 32767.0 / (10.0 * pi / 180.0),
                    Unit::radians);
            v.field("pan_tilt_chi_square", pan_tilt_chi_square, u8, 255.0 / 10.0);
        }
    }
};

}  // namespace gimbal::orion

namespace gimbal::orion {
using TelemetryPackets =
    PacketList<GeolocateTelemetry, Performance, Diagnostics, SoftwareDiagnostics, Vibration,
               NetworkDiagnostics, RetractStatus, StareStart, ResetSource, DebugString, KlvUserData,
               GpsData, InsQuality>;
}  // namespace gimbal::orion
