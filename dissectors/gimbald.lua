-- gimbald.lua: Wireshark dissectors for gimbald recordings (interface contract section 12).
--
--   tshark -X lua_script:gimbald.lua -r flight.pcapng
--   or copy to ~/.local/lib/wireshark/plugins/ (see docs/wireshark.md)
--
-- Registers the dissectors named by the recordings' exported-PDU records:
--   orion         Trillium OrionPublic packets: every packet of the ICD, every field in the
--                 units of contract section 1 (degrees, metres, seconds), enum names, Fletcher
--                 checksum verified. Field filters: orion.<packet>.<key>, e.g.
--                 orion.geolocate_telemetry.lat; keys are those of gimbald's JSON.
--   viewpro       Viewpro frames in both directions (mode/adjust commands, IN1..IN3, OUT1..OUT4).
--   mavlink       MAVLink v1/v2 header, message id and name.
--   gimbald-json  gimbald's JSON requests and replies (handed to Wireshark's json dissector).
--   orion-tcp     OrionPublic in live TCP captures (port 8747, or Decode As), reassembled.
--
-- The Orion part interprets a schema table generated from the codec's packet declarations
-- (lib/protocols/orion/codec/packets_*.hpp) by tools/gen-dissector; the block between the
-- GENERATED markers must not be edited by hand: `cmake --build build/debug --target
-- update-dissector`.

-- BEGIN GENERATED ORION SCHEMA (tools/gen-dissector from lib/protocols/orion/codec/packets_*.hpp; do not edit by hand:
-- cmake --build build/debug --target update-dissector)
local orion_enums = {
  [1] = { [0] = "disabled", [1] = "fault", [16] = "rate", [17] = "geo_rate", [32] = "ffc_auto", [33] = "ffc_manual", [48] = "scene", [49] = "track", [64] = "calibration", [80] = "position", [81] = "position_no_limits", [96] = "geopoint", [112] = "path", [113] = "down", [255] = "unknown", },
  [2] = { [0] = "none", [1] = "skylink", [2] = "laser", [3] = "other", [4] = "internal", [5] = "internal_dted", },
  [3] = { [0] = "in_gimbal_native", [1] = "in_platform", [2] = "in_payload_ball", },
  [4] = { [0] = "none", [1] = "clevis", [2] = "crown", [3] = "payload", [4] = "lensctrl", [5] = "misscomp", },
  [5] = { [0] = "disable", [1] = "deploy", [2] = "retract", },
  [6] = { [0] = "disabled", [1] = "retracted", [2] = "retracting", [3] = "deploying", [4] = "deployed", [5] = "fault", },
  [7] = { [0] = "log", [1] = "info", [2] = "warn", [3] = "error", [4] = "fatal", },
  [8] = { [0] = "no_fix", [1] = "dead_reckoning_only", [2] = "two_d_fix", [3] = "three_d_fix", [4] = "gnss_dead_reckoning", [5] = "time_only", },
  [9] = { [0] = "external_source", [1] = "ublox_source", [2] = "mavlink_source", [3] = "nmea_source", [4] = "novatel_source", [5] = "autopilot_source", [6] = "piksi_source", },
  [10] = { [0] = "internal", [1] = "sensonor", [2] = "dmu11", [3] = "external", [4] = "epson", },
  [11] = { [0] = "init1", [1] = "init2", [2] = "ahrs", [3] = "run_hard", [4] = "run", [5] = "run_tight", },
  [12] = { [0] = "none", [1] = "stare", [2] = "closure", [3] = "stare_closure", },
  [13] = { [0] = "manual", [1] = "ssn_no_motion", [2] = "ssn_low", [3] = "ssn_medium", [4] = "ssn_high", },
  [14] = { [0] = "ethernet", [2] = "primary", [3] = "fp2", [4] = "fp1", [8] = "fp3", [9] = "fp4", [255] = "current", },
  [15] = { [0] = "none", [1] = "pointer", [2] = "10mj_marker", [3] = "lightware", [4] = "jenoptik_dlem", [5] = "vectronix", },
  [16] = { [0] = "no_change", [1] = "none", [2] = "default", [3] = "orion", [4] = "clevis", [5] = "clevis_raw", [6] = "nmea_gps", [7] = "ublox_gps", [8] = "novatel_gps", [9] = "mavlink_gps", [10] = "um7_mag", [11] = "sightline_video", [12] = "sensonor_imu", [13] = "dmu11_imu", [14] = "discovery", [15] = "airrobot", [16] = "proprietary1", [17] = "proprietary2", [18] = "flir", [19] = "epson_imu", [20] = "piksi", [21] = "wepilot", },
  [17] = { [0] = "h264", [1] = "mjpeg", [2] = "raw", [3] = "yuv", },
  [18] = { [0] = "none", [1] = "visible", [2] = "swir", [3] = "mwir", [4] = "lwir", },
  [19] = { [0] = "unknown", [1] = "flir", [2] = "aptina", [3] = "zafiro", [4] = "hitachi", [5] = "bae", [6] = "sony", [7] = "ktnc", },
}
local orion_packets = {
  [1] = { name = "cmd", min = 7, max = 7, fields = {
    { kind = "field", key = "target", enc = "i", size = 2, factor = 1000, radians = true, member = "float", n = 2 },
    { kind = "field", key = "mode", enc = "u", size = 1, member = "enum", enum = 1 },
    { kind = "field", key = "stabilized", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "impulse_time_s", enc = "u", size = 1, factor = 10, member = "float" },
  } },
  [2] = { name = "uart_config", min = 5, max = 6, fields = {
    { kind = "field", key = "port", enc = "u", size = 1, member = "enum", enum = 14 },
    { kind = "field", key = "baud", enc = "u", size = 3, member = "int" },
    { kind = "field", key = "protocol", enc = "u", size = 1, member = "enum", enum = 16 },
    { kind = "optional" },
    { kind = "field", key = "temporary", enc = "u", size = 1, member = "bool" },
  } },
  [3] = { name = "laser_cmd", min = 11, max = 29, fields = {
    { kind = "reserved", key = "reserved", size = 2 },
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
    { kind = "string", key = "password", max = 16 },
    { kind = "field", key = "enable", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "arm", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "fire", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "on_time_ms", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "off_time_ms", enc = "u", size = 2, member = "int" },
    { kind = "optional" },
    { kind = "field", key = "prf_code", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "safety_bypass", enc = "u", size = 1, member = "bool" },
  } },
  [6] = { name = "laser_states", min = 1, max = 13, fields = {
    { kind = "count", key = "num_lasers", enc = "u", size = 1, member = "int", max = 2 },
    { kind = "group", key = "states", count = "num_lasers", fields = {
        { kind = "field", key = "type", enc = "u", size = 1, member = "enum", enum = 15 },
        { kind = "bits", key = "enabled", member = "bool", width = 1 },
        { kind = "bits", key = "armed", member = "bool", width = 1 },
        { kind = "bits", key = "active", member = "bool", width = 1 },
        { kind = "bits", key = "ground_speed_lock", member = "bool", width = 1 },
        { kind = "bits", key = "altitude_lock", member = "bool", width = 1 },
        { kind = "bits", key = "password_lock", member = "bool", width = 1 },
        { kind = "bits", key = "ap_comm_lock", member = "bool", width = 1 },
        { kind = "bits", key = "ap_flying_lock", member = "bool", width = 1 },
        { kind = "bits", key = "bypass_enabled", member = "bool", width = 1 },
        { kind = "bits", key = "pitch_angle_lock", member = "bool", width = 1 },
        { kind = "reserved_bits", key = "reserved", width = 14 },
        { kind = "field", key = "wait_timer_ms", enc = "u", size = 2, member = "int" },
      } },
  } },
  [7] = { name = "startup_cmd", min = 7, max = 7, fields = {
    { kind = "field", key = "target", enc = "i", size = 2, factor = 1000, radians = true, member = "float", n = 2 },
    { kind = "field", key = "mode", enc = "u", size = 1, member = "enum", enum = 1 },
    { kind = "field", key = "stabilized", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "impulse_time_s", enc = "u", size = 1, factor = 10, member = "float" },
  } },
  [34] = { name = "limits", min = 32, max = 34, fields = {
    { kind = "field", key = "min_pos", enc = "i", size = 2, factor = 1000, radians = true, member = "float", n = 2 },
    { kind = "field", key = "max_pos", enc = "i", size = 2, factor = 1000, radians = true, member = "float", n = 2 },
    { kind = "field", key = "max_vel", enc = "u", size = 2, factor = 1000, radians = true, member = "float", n = 2 },
    { kind = "field", key = "max_accel", enc = "u", size = 2, radians = true, member = "float", n = 2 },
    { kind = "field", key = "cont_cur", enc = "u", size = 2, factor = 1000, member = "float", n = 2 },
    { kind = "field", key = "peak_cur", enc = "u", size = 2, factor = 1000, member = "float", n = 2 },
    { kind = "field", key = "peak_cur_time_s", enc = "u", size = 2, factor = 1000, member = "float", n = 2 },
    { kind = "field", key = "init_cur", enc = "u", size = 2, factor = 1000, member = "float", n = 2 },
    { kind = "optional" },
    { kind = "field", key = "max_power", enc = "u", size = 1, member = "float", n = 2 },
  } },
  [37] = { name = "clevis_version", min = 32, max = 36, fields = {
    { kind = "fixed_string", key = "version", size = 16 },
    { kind = "fixed_string", key = "part_number", size = 16 },
    { kind = "optional" },
    { kind = "field", key = "on_time_min", enc = "u", size = 4, member = "int" },
  } },
  [38] = { name = "reset_source", min = 8, max = 9, fields = {
    { kind = "field", key = "vector", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "address", enc = "u", size = 4, member = "int" },
    { kind = "optional" },
    { kind = "field", key = "source_board", enc = "u", size = 1, member = "enum", enum = 4 },
  } },
  [39] = { name = "board", min = 20, max = 20, fields = {
    { kind = "field", key = "board_sn", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "assembly_sn", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "config", enc = "u", size = 4, member = "int" },
    { kind = "reserved", key = "reserved", size = 3 },
    { kind = "field", key = "board", enc = "u", size = 1, member = "enum", enum = 4 },
    { kind = "bits", key = "manufacture_year", member = "int", width = 7 },
    { kind = "bits", key = "manufacture_month", member = "int", width = 4 },
    { kind = "bits", key = "manufacture_day", member = "int", width = 5 },
    { kind = "bits", key = "calibration_year", member = "int", width = 7 },
    { kind = "bits", key = "calibration_month", member = "int", width = 4 },
    { kind = "bits", key = "calibration_day", member = "int", width = 5 },
  } },
  [40] = { name = "crown_version", min = 32, max = 36, fields = {
    { kind = "fixed_string", key = "version", size = 16 },
    { kind = "fixed_string", key = "part_number", size = 16 },
    { kind = "optional" },
    { kind = "field", key = "on_time_min", enc = "u", size = 4, member = "int" },
  } },
  [41] = { name = "payload_version", min = 40, max = 44, fields = {
    { kind = "fixed_string", key = "version", size = 24 },
    { kind = "fixed_string", key = "part_number", size = 16 },
    { kind = "optional" },
    { kind = "field", key = "on_time_min", enc = "u", size = 4, member = "int" },
  } },
  [44] = { name = "tracker_version", min = 32, max = 32, fields = {
    { kind = "fixed_string", key = "version", size = 16 },
    { kind = "fixed_string", key = "part_number", size = 16 },
  } },
  [65] = { name = "diagnostics", min = 28, max = 28, fields = {
    { kind = "field", key = "voltage24", enc = "u", size = 2, factor = 1000, member = "float" },
    { kind = "field", key = "voltage12", enc = "u", size = 2, factor = 1000, member = "float" },
    { kind = "field", key = "voltage3v3", enc = "u", size = 2, factor = 1000, member = "float" },
    { kind = "field", key = "current24", enc = "u", size = 2, factor = 1000, member = "float" },
    { kind = "field", key = "current12", enc = "u", size = 2, factor = 1000, member = "float" },
    { kind = "field", key = "current3v3", enc = "u", size = 2, factor = 1000, member = "float" },
    { kind = "field", key = "crown_temp", enc = "i", size = 1, member = "float" },
    { kind = "field", key = "sla_temp", enc = "i", size = 1, member = "float" },
    { kind = "field", key = "gyro_temp", enc = "i", size = 1, member = "float" },
    { kind = "reserved", key = "reserved", size = 1 },
    { kind = "field", key = "voltage24_var", enc = "u", size = 2, factor = 100000, member = "float" },
    { kind = "field", key = "voltage12_var", enc = "u", size = 2, factor = 100000, member = "float" },
    { kind = "field", key = "voltage3v3_var", enc = "u", size = 2, factor = 100000, member = "float" },
    { kind = "field", key = "current24_var", enc = "u", size = 2, factor = 100000, member = "float" },
    { kind = "field", key = "current12_var", enc = "u", size = 2, factor = 100000, member = "float" },
    { kind = "field", key = "current3v3_var", enc = "u", size = 2, factor = 100000, member = "float" },
  } },
  [67] = { name = "performance", min = 20, max = 20, fields = {
    { kind = "field", key = "rms_quad", enc = "u", size = 2, factor = 1000000, member = "float", n = 2 },
    { kind = "field", key = "rms_dir", enc = "u", size = 2, factor = 1000000, member = "float", n = 2 },
    { kind = "field", key = "rms_vel", enc = "u", size = 2, factor = 1000, member = "float", n = 2 },
    { kind = "field", key = "rms_pos", enc = "u", size = 2, factor = 1000000, member = "float", n = 2 },
    { kind = "field", key = "iout", enc = "u", size = 2, factor = 1000, member = "float", n = 2 },
  } },
  [68] = { name = "software_diagnostics", min = 4, max = 134, fields = {
    { kind = "field", key = "source_board", enc = "u", size = 1, member = "enum", enum = 4 },
    { kind = "count", key = "num_cores", enc = "u", size = 1, member = "int", max = 2 },
    { kind = "reserved", key = "reserved", size = 2 },
    { kind = "group", key = "cores", count = "num_cores", fields = {
        { kind = "field", key = "cpu_load", enc = "u", size = 1, factor = 2.5499999999999998, member = "float" },
        { kind = "field", key = "heap_load", enc = "u", size = 1, factor = 2.5499999999999998, member = "float" },
        { kind = "field", key = "stack_load", enc = "u", size = 1, factor = 2.5499999999999998, member = "float" },
        { kind = "reserved", key = "reserved", size = 1 },
        { kind = "count", key = "num_threads", enc = "u", size = 1, member = "int", max = 10 },
        { kind = "group", key = "threads", count = "num_threads", fields = {
            { kind = "field", key = "cpu_load", enc = "u", size = 1, factor = 2.5499999999999998, member = "float" },
            { kind = "field", key = "heap_load", enc = "u", size = 1, factor = 2.5499999999999998, member = "float" },
            { kind = "field", key = "stack_load", enc = "u", size = 1, factor = 2.5499999999999998, member = "float" },
            { kind = "field", key = "watchdog_left", enc = "u", size = 1, factor = 2.5499999999999998, member = "float" },
            { kind = "field", key = "num_iterations", enc = "u", size = 1, factor = 0.10000000000000001, member = "float" },
            { kind = "field", key = "worstcase", enc = "u", size = 1, factor = 10, member = "float" },
          } },
      } },
  } },
  [69] = { name = "vibration", min = 140, max = 140, fields = {
    { kind = "field", key = "max_accel", enc = "i", size = 2, factor = 1638.3499999999999, member = "float", n = 3 },
    { kind = "field", key = "max_gyro", enc = "i", size = 2, factor = 327670, radians = true, member = "float", n = 3 },
    { kind = "group", key = "fft_data", n = 16, fields = {
        { kind = "field", key = "frequency", enc = "u", size = 2, factor = 327.67500000000001, member = "float" },
        { kind = "field", key = "accel", enc = "u", size = 1, factor = 255, member = "float", n = 3 },
        { kind = "field", key = "gyro", enc = "u", size = 1, factor = 255, member = "float", n = 3 },
      } },
  } },
  [70] = { name = "network_diagnostics", min = 36, max = 36, fields = {
    { kind = "field", key = "flags", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "rx_bytes", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "tx_bytes", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "rx_packets", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "tx_packets", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "rx_errors", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "tx_errors", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "rx_drops", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "tx_drops", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "rx_fifo_errors", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "tx_fifo_errors", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "frame_errors", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "collisions", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "carrier_errors", enc = "u", size = 2, member = "int" },
  } },
  [96] = { name = "camera_switch", min = 1, max = 1, fields = {
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
  } },
  [97] = { name = "camera_state", min = 2, max = 5, fields = {
    { kind = "field", key = "zoom", enc = "i", size = 2, factor = 100, member = "float" },
    { kind = "optional" },
    { kind = "field", key = "focus", enc = "i", size = 2, factor = 10000, member = "float" },
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
  } },
  [98] = { name = "network_video", min = 6, max = 14, fields = {
    { kind = "ipv4", key = "dest_ip", enc = "u", size = 4 },
    { kind = "field", key = "port", enc = "u", size = 2, member = "int" },
    { kind = "optional" },
    { kind = "field", key = "bitrate", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "ttl", enc = "i", size = 1, member = "int" },
    { kind = "field", key = "stream_type", enc = "u", size = 1, member = "enum", enum = 17 },
    { kind = "field", key = "mjpeg_quality", enc = "u", size = 1, member = "int" },
    { kind = "bits", key = "save_settings", member = "bool", width = 1 },
    { kind = "bits", key = "ts_packet_count", member = "int", width = 4 },
  } },
  [99] = { name = "cameras", min = 4, max = 52, fields = {
    { kind = "count", key = "num_cameras", enc = "u", size = 1, member = "int", max = 2 },
    { kind = "reserved", key = "reserved", size = 3 },
    { kind = "group", key = "cameras", count = "num_cameras", fields = {
        { kind = "field", key = "type", enc = "u", size = 1, member = "enum", enum = 18 },
        { kind = "field", key = "protocol", enc = "u", size = 1, member = "enum", enum = 19 },
        { kind = "field", key = "min_focal_length_mm", enc = "u", size = 4, factor = 1000, member = "float" },
        { kind = "field", key = "max_focal_length_mm", enc = "u", size = 4, factor = 1000, member = "float" },
        { kind = "field", key = "pixel_pitch_mm", enc = "u", size = 2, factor = 1000000, member = "float" },
        { kind = "field", key = "array_width", enc = "u", size = 2, member = "int" },
        { kind = "field", key = "array_height", enc = "u", size = 2, member = "int" },
        { kind = "field", key = "align_min", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float", n = 2 },
        { kind = "field", key = "align_max", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float", n = 2 },
      } },
  } },
  [103] = { name = "flir_settings", min = 5, max = 7, fields = {
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
    { kind = "reserved_bits", key = "reserved", width = 1 },
    { kind = "bits", key = "palette", member = "int", width = 3 },
    { kind = "bits", key = "nuc_type", member = "enum", enum = 13, width = 3 },
    { kind = "bits", key = "black_hot", member = "bool", width = 1 },
    { kind = "field", key = "max_agc_gain", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "ace_level", enc = "i", size = 1, member = "int" },
    { kind = "field", key = "dde_threshold", enc = "u", size = 1, member = "int" },
    { kind = "optional" },
    { kind = "field", key = "agc_midpoint", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "integration_time_ms", enc = "u", size = 1, factor = 8.7931034482758612, offset = 1, member = "float" },
  } },
  [104] = { name = "aptina_settings", min = 13, max = 15, fields = {
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "min_exposure_ms", enc = "u", size = 2, factor = 1988.9226100151743, offset = 0.050000000000000003, member = "float" },
    { kind = "field", key = "max_exposure_ms", enc = "u", size = 2, factor = 1988.9226100151743, offset = 0.050000000000000003, member = "float" },
    { kind = "field", key = "min_gain", enc = "u", size = 2, factor = 2114.0322580645161, offset = 1, member = "float" },
    { kind = "field", key = "max_gain", enc = "u", size = 2, factor = 2114.0322580645161, offset = 1, member = "float" },
    { kind = "field", key = "brightness", enc = "i", size = 1, member = "int" },
    { kind = "field", key = "contrast", enc = "i", size = 1, factor = 127, member = "float" },
    { kind = "field", key = "saturation", enc = "i", size = 1, factor = 127, member = "float" },
    { kind = "field", key = "sharpness", enc = "u", size = 1, factor = 51, member = "float" },
    { kind = "optional" },
    { kind = "bits", key = "debug_enable", member = "bool", width = 1 },
    { kind = "field", key = "hue", enc = "i", size = 1, member = "int" },
  } },
  [105] = { name = "zafiro_settings", min = 6, max = 7, fields = {
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "black_hot", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "integration_time_ms", enc = "u", size = 1, factor = 8.7931034482758612, offset = 1, member = "float" },
    { kind = "field", key = "lap_enabled", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "lap_gain", enc = "u", size = 1, factor = 72.857142857142861, offset = 0.5, member = "float" },
    { kind = "field", key = "agc_saturation", enc = "u", size = 1, factor = 2550, member = "float" },
    { kind = "optional" },
    { kind = "field", key = "use_nuc_table_presets", enc = "u", size = 1, member = "bool" },
  } },
  [106] = { name = "hitachi_settings", min = 5, max = 6, fields = {
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "integration_time_us", enc = "i", size = 2, member = "int" },
    { kind = "field", key = "aperture", enc = "i", size = 2, factor = 10, member = "float" },
    { kind = "optional" },
    { kind = "field", key = "sharpness", enc = "u", size = 1, factor = 51, member = "float" },
  } },
  [108] = { name = "sony_settings", min = 12, max = 12, fields = {
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "min_exposure_ms", enc = "u", size = 2, factor = 1988.9226100151743, offset = 0.050000000000000003, member = "float" },
    { kind = "field", key = "max_exposure_ms", enc = "u", size = 2, factor = 1988.9226100151743, offset = 0.050000000000000003, member = "float" },
    { kind = "field", key = "min_gain_db", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "max_gain_db", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "brightness", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "contrast", enc = "i", size = 1, factor = 127, member = "float" },
    { kind = "field", key = "saturation", enc = "i", size = 1, factor = 127, member = "float" },
    { kind = "field", key = "sharpness", enc = "u", size = 1, factor = 51, member = "float" },
    { kind = "field", key = "frame_rate_hz", enc = "u", size = 1, factor = 8.5, member = "float" },
  } },
  [109] = { name = "ktnc_settings", min = 5, max = 11, fields = {
    { kind = "field", key = "index", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "integration_time_us", enc = "i", size = 2, member = "int" },
    { kind = "field", key = "aperture", enc = "i", size = 2, factor = 10, member = "float" },
    { kind = "optional" },
    { kind = "field", key = "sharpness", enc = "u", size = 1, factor = 15.9375, member = "float" },
    { kind = "field", key = "vertical_flip", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "exposure_comp", enc = "u", size = 1, factor = 18.214285714285715, member = "float" },
    { kind = "field", key = "contrast", enc = "u", size = 1, factor = 7.96875, member = "float" },
    { kind = "field", key = "saturation", enc = "u", size = 1, factor = 7.96875, member = "float" },
    { kind = "bits", key = "night_mode", member = "bool", width = 1 },
    { kind = "bits", key = "reset_to_defaults", member = "bool", width = 1 },
  } },
  [128] = { name = "autopilot_data", min = 4, max = 4, fields = {
    { kind = "field", key = "is_flying", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "comm_good", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "agl", enc = "i", size = 2, member = "int" },
  } },
  [160] = { name = "retract_cmd", min = 2, max = 2, fields = {
    { kind = "field", key = "cmd", enc = "u", size = 1, member = "enum", enum = 5 },
    { kind = "reserved", key = "reserved", size = 1 },
  } },
  [161] = { name = "retract_status", min = 6, max = 6, fields = {
    { kind = "field", key = "cmd", enc = "u", size = 1, member = "enum", enum = 5 },
    { kind = "field", key = "state", enc = "u", size = 1, member = "enum", enum = 6 },
    { kind = "field", key = "pos", enc = "i", size = 2, factor = 1000, radians = true, member = "float" },
    { kind = "field", key = "flags", enc = "u", size = 2, member = "int" },
  } },
  [177] = { name = "debug_string", min = 5, max = 132, fields = {
    { kind = "field", key = "source", enc = "u", size = 1, member = "enum", enum = 4 },
    { kind = "field", key = "priority", enc = "u", size = 1, member = "enum", enum = 7 },
    { kind = "reserved", key = "reserved", size = 1 },
    { kind = "reserved", key = "reserved", size = 1 },
    { kind = "string", key = "description", max = 128 },
  } },
  [178] = { name = "user_data", min = 6, max = 134, fields = {
    { kind = "field", key = "port", enc = "u", size = 1, member = "enum", enum = 14 },
    { kind = "count", key = "size", enc = "u", size = 1, member = "int", max = 128 },
    { kind = "field", key = "id", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "data", enc = "u", size = 1, member = "int", count = "size" },
  } },
  [179] = { name = "klv_user_data", min = 3, max = 130, fields = {
    { kind = "field", key = "key", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "sub_key", enc = "u", size = 1, member = "int" },
    { kind = "count", key = "length", enc = "u", size = 1, member = "int", max = 127 },
    { kind = "field", key = "value", enc = "u", size = 1, member = "int", count = "length" },
  } },
  [209] = { name = "gps_data", min = 54, max = 69, fields = {
    { kind = "bits", key = "multi_ant_heading_valid", member = "bool", width = 1 },
    { kind = "reserved_bits", key = "reserved", width = 3 },
    { kind = "bits", key = "fix_type", member = "enum", enum = 8, width = 4 },
    { kind = "field", key = "fix_state", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "tracked_sats", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "pdop", enc = "u", size = 1, factor = 10, member = "float" },
    { kind = "field", key = "lat", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "lon", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "alt", enc = "i", size = 4, factor = 10000, member = "float" },
    { kind = "field", key = "vel_ned", enc = "i", size = 4, factor = 1000, member = "float", n = 3 },
    { kind = "field", key = "hacc", enc = "i", size = 4, factor = 1000, member = "float" },
    { kind = "field", key = "vacc", enc = "i", size = 4, factor = 1000, member = "float" },
    { kind = "field", key = "speed_acc", enc = "i", size = 4, factor = 1000, member = "float" },
    { kind = "field", key = "heading_acc", enc = "i", size = 4, factor = 5729578, radians = true, member = "float" },
    { kind = "field", key = "itow_ms", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "week", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "geoid_undulation", enc = "i", size = 2, factor = 100, member = "float" },
    { kind = "field", key = "source", enc = "u", size = 1, member = "enum", enum = 9 },
    { kind = "reserved_bits", key = "reserved", width = 6 },
    { kind = "bits", key = "detailed_accuracy_valid", member = "bool", width = 1 },
    { kind = "bits", key = "vertical_velocity_valid", member = "bool", width = 1 },
    { kind = "optional" },
    { kind = "field", key = "leap_seconds", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "multi_ant_heading", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float", cond = { key = "multi_ant_heading_valid", present = false, values = { 0 } } },
    { kind = "field", key = "pos_accuracy", enc = "u", size = 2, factor = 1000, member = "float", n = 3, cond = { key = "detailed_accuracy_valid", present = false, values = { 0 } } },
    { kind = "field", key = "vel_accuracy", enc = "u", size = 2, factor = 1000, member = "float", n = 3, cond = { key = "detailed_accuracy_valid", present = false, values = { 0 } } },
  } },
  [210] = { name = "ext_heading_data", min = 4, max = 8, fields = {
    { kind = "field", key = "ext_heading", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
    { kind = "field", key = "noise", enc = "u", size = 2, factor = 10430.219195527361, radians = true, member = "float" },
    { kind = "optional" },
    { kind = "bits", key = "heading_in_gimbal_axis", member = "bool", width = 1 },
    { kind = "bits", key = "heading_from_align", member = "bool", width = 1 },
    { kind = "reserved_bits", key = "reserved", width = 14 },
    { kind = "field", key = "pitch", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
  } },
  [211] = { name = "ins_quality", min = 34, max = 79, fields = {
    { kind = "field", key = "system_time_ms", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "gps_source", enc = "u", size = 1, member = "enum", enum = 9 },
    { kind = "reserved_bits", key = "reserved", width = 5 },
    { kind = "bits", key = "imu_type", member = "enum", enum = 10, width = 3 },
    { kind = "field", key = "ins_mode", enc = "u", size = 1, member = "enum", enum = 11 },
    { kind = "bits", key = "has_gyro_bias", member = "bool", width = 1 },
    { kind = "bits", key = "has_gravity_bias", member = "bool", width = 1 },
    { kind = "bits", key = "has_accel_bias", member = "bool", width = 1 },
    { kind = "bits", key = "has_clock_bias", member = "bool", width = 1 },
    { kind = "bits", key = "has_pan_tilt_bias", member = "bool", width = 1 },
    { kind = "bits", key = "pos_rejected", member = "bool", width = 1 },
    { kind = "bits", key = "vel_rejected", member = "bool", width = 1 },
    { kind = "bits", key = "hdg_rejected", member = "bool", width = 1 },
    { kind = "field", key = "gps_period_s", enc = "u", size = 1, factor = 100, member = "float" },
    { kind = "field", key = "hdg_period_s", enc = "u", size = 1, factor = 100, member = "float" },
    { kind = "field", key = "pos_chi_square", enc = "sf", size = 2, sig = 9, member = "float" },
    { kind = "field", key = "vel_chi_square", enc = "sf", size = 2, sig = 9, member = "float" },
    { kind = "field", key = "hdg_chi_square", enc = "sf", size = 2, sig = 9, member = "float" },
    { kind = "field", key = "att_confidence", enc = "u", size = 2, factor = 10000, radians = true, member = "float", n = 3 },
    { kind = "field", key = "vel_confidence", enc = "u", size = 2, factor = 100, member = "float", n = 3 },
    { kind = "field", key = "pos_confidence", enc = "u", size = 2, factor = 100, member = "float", n = 3 },
    { kind = "field", key = "gyro_confidence", enc = "u", size = 2, factor = 100000, radians = true, member = "float", n = 3, cond = { key = "has_gyro_bias", present = false, values = { 0 } } },
    { kind = "field", key = "accel_confidence", enc = "u", size = 2, factor = 30000, member = "float", n = 3, cond = { key = "has_accel_bias", present = false, values = { 0 } } },
    { kind = "field", key = "gravity_confidence", enc = "u", size = 2, factor = 30000, member = "float", cond = { key = "has_gravity_bias", present = false, values = { 0 } } },
    { kind = "field", key = "clock_bias_confidence", enc = "u", size = 2, factor = 10000, member = "float", cond = { key = "has_clock_bias", present = false, values = { 0 } } },
    { kind = "field", key = "clock_drift_confidence", enc = "u", size = 2, factor = 10000, member = "float", cond = { key = "has_clock_bias", present = false, values = { 0 } } },
    { kind = "field", key = "gyro_bias", enc = "i", size = 2, factor = 100000, radians = true, member = "float", n = 3, cond = { key = "has_gyro_bias", present = false, values = { 0 } } },
    { kind = "field", key = "accel_bias", enc = "u", size = 2, factor = 30000, member = "float", n = 3, cond = { key = "has_accel_bias", present = false, values = { 0 } } },
    { kind = "field", key = "gravity_bias", enc = "u", size = 2, factor = 30000, member = "float", cond = { key = "has_gravity_bias", present = false, values = { 0 } } },
    { kind = "field", key = "clock_bias", enc = "i", size = 2, factor = 100, member = "float", cond = { key = "has_clock_bias", present = false, values = { 0 } } },
    { kind = "field", key = "clock_drift", enc = "i", size = 2, factor = 1000, member = "float", cond = { key = "has_clock_bias", present = false, values = { 0 } } },
    { kind = "field", key = "num_tight_sat_pos_updates", enc = "u", size = 1, member = "int", cond = { key = "has_clock_bias", present = false, values = { 0 } } },
    { kind = "field", key = "num_tight_sat_vel_updates", enc = "u", size = 1, member = "int", cond = { key = "has_clock_bias", present = false, values = { 0 } } },
    { kind = "field", key = "num_tight_pos_updates", enc = "u", size = 1, member = "int", cond = { key = "has_clock_bias", present = false, values = { 0 } } },
    { kind = "field", key = "num_tight_vel_updates", enc = "u", size = 1, member = "int", cond = { key = "has_clock_bias", present = false, values = { 0 } } },
    { kind = "field", key = "pan_tilt_bias", enc = "i", size = 2, factor = 187741.08073051684, radians = true, member = "float", n = 2, cond = { key = "has_pan_tilt_bias", present = false, values = { 0 } } },
    { kind = "field", key = "pan_tilt_chi_square", enc = "u", size = 1, factor = 25.5, member = "float", cond = { key = "has_pan_tilt_bias", present = false, values = { 0 } } },
  } },
  [212] = { name = "geolocate_telemetry", min = 46, max = 89, fields = {
    { kind = "field", key = "system_time_ms", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "gps_itow_ms", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "gps_week", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "geoid_undulation", enc = "i", size = 2, factor = 273.05833333333334, member = "float" },
    { kind = "field", key = "lat", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "lon", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "alt", enc = "i", size = 4, factor = 10000, member = "float" },
    { kind = "field", key = "vel_ned", enc = "i", size = 2, factor = 100, member = "float", n = 3 },
    { kind = "field", key = "quat", enc = "i", size = 2, factor = 32767, member = "float", n = 4 },
    { kind = "field", key = "pan", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
    { kind = "field", key = "tilt", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
    { kind = "field", key = "hfov", enc = "u", size = 2, factor = 10430.219195527361, radians = true, member = "float" },
    { kind = "field", key = "vfov", enc = "u", size = 2, factor = 10430.219195527361, radians = true, member = "float" },
    { kind = "optional" },
    { kind = "field", key = "los_ecef", enc = "i", size = 2, member = "float", n = 3 },
    { kind = "field", key = "pixel_width", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "pixel_height", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "mode", enc = "u", size = 1, member = "enum", enum = 1 },
    { kind = "field", key = "path_progress", enc = "u", size = 1, factor = 255, member = "float" },
    { kind = "field", key = "stare_time_s", enc = "u", size = 1, factor = 100, member = "float" },
    { kind = "field", key = "path_from", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "path_to", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "image_shifts", enc = "i", size = 4, factor = 1000000, radians = true, member = "float", n = 2 },
    { kind = "field", key = "image_shift_delta_time_s", enc = "u", size = 2, factor = 1000, member = "float" },
    { kind = "field", key = "image_shift_confidence", enc = "u", size = 1, factor = 255, member = "float" },
    { kind = "field", key = "output_shifts", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float", n = 2 },
    { kind = "field", key = "range_source", enc = "u", size = 1, member = "enum", enum = 2 },
    { kind = "field", key = "leap_seconds", enc = "u", size = 1, member = "int" },
    { kind = "field", key = "pan_alignment", enc = "i", size = 1, factor = 1000, radians = true, member = "float" },
    { kind = "field", key = "tilt_alignment", enc = "i", size = 1, factor = 1000, radians = true, member = "float" },
    { kind = "field", key = "ins_rotation_option", enc = "u", size = 1, member = "enum", enum = 3 },
    { kind = "field", key = "ins_quat", enc = "i", size = 2, factor = 32767, member = "float", n = 4, cond = { key = "ins_rotation_option", present = false, values = { 0 } } },
  } },
  [213] = { name = "geopoint_cmd", min = 18, max = 21, fields = {
    { kind = "field", key = "lat", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "lon", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "alt", enc = "i", size = 4, factor = 10000, member = "float" },
    { kind = "field", key = "vel_ned", enc = "i", size = 2, factor = 100, member = "float", n = 3 },
    { kind = "optional" },
    { kind = "field", key = "joystick_range_m", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "options", enc = "u", size = 1, member = "enum", enum = 12 },
  } },
  [214] = { name = "range_data", min = 7, max = 7, fields = {
    { kind = "field", key = "range_m", enc = "u", size = 4, factor = 100, member = "float" },
    { kind = "field", key = "max_age_ms", enc = "u", size = 2, member = "int" },
    { kind = "field", key = "source", enc = "u", size = 1, member = "enum", enum = 2 },
  } },
  [215] = { name = "path", min = 2, max = 140, fields = {
    { kind = "count", key = "num_points", enc = "u", size = 1, member = "int", max = 15 },
    { kind = "bits", key = "point_down", member = "bool", width = 1 },
    { kind = "reserved_bits", key = "reserved", width = 3 },
    { kind = "bits", key = "num_cross_track_steps", member = "int", width = 4 },
    { kind = "group", key = "points", count = "num_points", fields = {
        { kind = "field", key = "pos_ecef", enc = "i", size = 3, member = "float", n = 3 },
      } },
    { kind = "optional" },
    { kind = "field", key = "along_track_step_angle", enc = "u", size = 2, factor = 20860.438391054722, radians = true, member = "float" },
    { kind = "field", key = "cross_track_step_ratio", enc = "u", size = 1, factor = 100, member = "float" },
  } },
  [216] = { name = "ins_options", min = 12, max = 28, fields = {
    { kind = "bits", key = "enable_platform_rotation", member = "bool", width = 1 },
    { kind = "bits", key = "enable_course_is_heading", member = "bool", width = 1 },
    { kind = "bits", key = "disable_magnetometer", member = "bool", width = 1 },
    { kind = "bits", key = "disable_gps", member = "bool", width = 1 },
    { kind = "bits", key = "reset_ins", member = "bool", width = 1 },
    { kind = "bits", key = "disable_gps_clock_error", member = "bool", width = 1 },
    { kind = "bits", key = "enable_accel_bias", member = "bool", width = 1 },
    { kind = "bits", key = "enable_tightly_coupled", member = "bool", width = 1 },
    { kind = "bits", key = "use_phase_for_velocity", member = "bool", width = 1 },
    { kind = "bits", key = "disable_l1", member = "bool", width = 1 },
    { kind = "bits", key = "disable_l2", member = "bool", width = 1 },
    { kind = "bits", key = "disable_l5", member = "bool", width = 1 },
    { kind = "bits", key = "elevation_mask_code", member = "int", width = 4 },
    { kind = "bits", key = "enable_payload_ins", member = "bool", width = 1 },
    { kind = "bits", key = "enable_non_linear_heading", member = "bool", width = 1 },
    { kind = "bits", key = "enable_sensonor_mv", member = "bool", width = 1 },
    { kind = "bits", key = "enable_hd25_payload_ins", member = "bool", width = 1 },
    { kind = "bits", key = "optical_flow_setting", member = "int", width = 4 },
    { kind = "reserved_bits", key = "reserved", width = 8 },
    { kind = "field", key = "gimbal_to_platform_euler", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float", n = 3 },
    { kind = "field", key = "initial_heading", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
    { kind = "optional" },
    { kind = "field", key = "gps_lever_arm", enc = "i", size = 2, factor = 1000, member = "float", n = 3 },
    { kind = "field", key = "heading_observation_bias_angle", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
    { kind = "field", key = "second_gps_lever_arm", enc = "i", size = 2, factor = 1000, member = "float", n = 3 },
    { kind = "field", key = "align_heading_noise", enc = "u", size = 2, factor = 20860.438391054722, radians = true, member = "float" },
  } },
  [217] = { name = "stare_start", min = 20, max = 52, fields = {
    { kind = "field", key = "system_time_ms", enc = "u", size = 4, member = "int" },
    { kind = "field", key = "max_stare_time_s", enc = "u", size = 1, factor = 100, member = "float" },
    { kind = "bits", key = "along_track_stare", member = "bool", width = 1 },
    { kind = "bits", key = "prev_stare_terminated_by_time", member = "bool", width = 1 },
    { kind = "bits", key = "stare_started_by_time", member = "bool", width = 1 },
    { kind = "bits", key = "gimbal_data_valid", member = "bool", width = 1 },
    { kind = "bits", key = "stare_reset", member = "bool", width = 1 },
    { kind = "field", key = "prev_stare_time_s", enc = "u", size = 1, factor = 100, member = "float" },
    { kind = "field", key = "stare_load", enc = "u", size = 1, factor = 255, member = "float" },
    { kind = "field", key = "lat", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "lon", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "alt", enc = "i", size = 4, factor = 10000, member = "float" },
    { kind = "optional" },
    { kind = "field", key = "gimbal_lat", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "gimbal_lon", enc = "i", size = 4, factor = 572957795.13082325, radians = true, member = "float" },
    { kind = "field", key = "gimbal_alt", enc = "i", size = 4, factor = 10000, member = "float" },
    { kind = "field", key = "gimbal_quat", enc = "i", size = 2, factor = 32767, member = "float", n = 4 },
    { kind = "field", key = "pan", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
    { kind = "field", key = "tilt", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
    { kind = "field", key = "range_source", enc = "u", size = 1, member = "enum", enum = 2 },
    { kind = "field", key = "slant_range", enc = "u", size = 3, factor = 100, member = "float" },
    { kind = "field", key = "along_stare_angle", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
    { kind = "field", key = "cross_stare_angle", enc = "i", size = 2, factor = 10430.060040584269, radians = true, member = "float" },
  } },
  [218] = { name = "stare_ack", min = 4, max = 4, fields = {
    { kind = "field", key = "echo_system_time_ms", enc = "u", size = 4, member = "int" },
  } },
  [228] = { name = "network_settings", min = 12, max = 15, fields = {
    { kind = "ipv4", key = "ip", enc = "u", size = 4 },
    { kind = "ipv4", key = "mask", enc = "u", size = 4 },
    { kind = "ipv4", key = "gateway", enc = "u", size = 4 },
    { kind = "optional" },
    { kind = "field", key = "low_delay", enc = "u", size = 1, member = "bool" },
    { kind = "field", key = "mtu", enc = "u", size = 2, member = "int" },
  } },
  [248] = { name = "retract_version", min = 16, max = 16, fields = {
    { kind = "fixed_string", key = "version", size = 16 },
  } },
  [249] = { name = "lensctl_version", min = 16, max = 16, fields = {
    { kind = "fixed_string", key = "version", size = 16 },
  } },
}
-- END GENERATED ORION SCHEMA

-- Installed in Wireshark's global plugin folder and also named with -X lua_script: load once
-- (a second Proto("orion") would be an error). When the two copies differ, say which one runs:
-- a test of a working copy must not silently test an older installed one.
local function file_fingerprint()
    local source = debug.getinfo(1, "S").source
    local f = source:sub(1, 1) == "@" and io.open(source:sub(2), "rb")
    if not f then return source end
    local text = f:read("*a")
    f:close()
    local h = 0
    for i = 1, #text do h = (h * 31 + text:byte(i)) % 4294967291 end
    return string.format("%d:%d", #text, h)
end
local this_copy = { path = debug.getinfo(1, "S").source:sub(2), fingerprint = file_fingerprint() }
if _G.gimbald_dissectors_loaded then
    local loaded = _G.gimbald_dissectors_loaded
    if loaded.fingerprint ~= this_copy.fingerprint then
        report_failure("Lua: gimbald.lua: " .. this_copy.path .. " differs from the copy already " ..
                       "loaded (" .. loaded.path .. "), which is the one in use")
    end
    return
end
_G.gimbald_dissectors_loaded = this_copy  -- _G: each script has its own environment

local rad2deg = 180.0 / math.pi

------------------------------------------------------------------------------------------------
-- OrionPublic
------------------------------------------------------------------------------------------------

-- Packet ids the ICD lists without a layout (only requests or not documented).
local orion_names_without_layout = {
    [0] = "initialize", [4] = "reset", [66] = "faults", [107] = "bae_settings",
}

local orion_proto = Proto("orion", "Trillium OrionPublic")

local orion_id_names = {}
for id, name in pairs(orion_names_without_layout) do orion_id_names[id] = name end
for id, p in pairs(orion_packets) do orion_id_names[id] = p.name end

local of = {
    sync = ProtoField.uint16("orion.sync", "Sync", base.HEX),
    id = ProtoField.uint8("orion.id", "Packet id", base.DEC, orion_id_names),
    packet = ProtoField.string("orion.packet", "Packet"),
    length = ProtoField.uint8("orion.length", "Data length", base.DEC),
    request = ProtoField.bool("orion.request", "Request (zero-length packet)"),
    checksum = ProtoField.uint16("orion.checksum", "Checksum", base.HEX),
    checksum_computed = ProtoField.uint16("orion.checksum.computed", "Computed checksum", base.HEX),
    checksum_status = ProtoField.string("orion.checksum.status", "Checksum status"),
    extra = ProtoField.bytes("orion.extra", "Bytes after the known fields"),
    data = ProtoField.bytes("orion.data", "Data"),
}
local orion_expert = {
    bad_checksum = ProtoExpert.new("orion.checksum.bad", "Bad Orion checksum",
                                   expert.group.CHECKSUM, expert.severity.WARN),
    short = ProtoExpert.new("orion.short", "Orion packet too short for its fields",
                            expert.group.MALFORMED, expert.severity.ERROR),
    truncated = ProtoExpert.new("orion.truncated", "Orion frame shorter than its length byte",
                                expert.group.MALFORMED, expert.severity.ERROR),
    bad_sync = ProtoExpert.new("orion.sync.bad", "Orion sync bytes are not D0 0D",
                               expert.group.MALFORMED, expert.severity.ERROR),
    unknown = ProtoExpert.new("orion.unknown", "Orion packet id without a known layout",
                              expert.group.UNDECODED, expert.severity.NOTE),
    extra = ProtoExpert.new("orion.extra_bytes", "Bytes after the known fields (newer firmware?)",
                            expert.group.PROTOCOL, expert.severity.NOTE),
}

local orion_fields = {}  -- abbreviation -> ProtoField

-- How a field is carried, for the field's description (Wireshark shows it as the blurb).
local function wire_text(e)
    local t
    if e.kind == "bits" then
        t = "B" .. e.width
    elseif e.enc == "sf" then
        t = "F" .. (8 * e.size) .. ":" .. e.sig
    elseif e.enc == "f32" or e.enc == "f64" then
        t = "IEEE " .. e.enc
    elseif e.enc then
        t = (e.enc == "i" and "I" or "U") .. (8 * e.size)
    else
        t = e.kind
    end
    if e.factor then t = t .. string.format(", scaled by %.10g", e.factor) end
    if e.offset then t = t .. string.format(" from %.10g", e.offset) end
    if e.radians then t = t .. ", radians on the wire, degrees here" end
    if e.cond then t = t .. ", only if " .. e.cond.key .. (e.cond.present and " is " or " is not ")
                          .. table.concat(e.cond.values, "/") end
    return t
end

-- One ProtoField per declared key: doubles for scaled values (already in contract units),
-- strings for enum names (filter with orion.geolocate_telemetry.mode == "geopoint").
local function make_orion_fields(prefix, entries)
    for _, e in ipairs(entries) do
        local abbr = prefix .. "." .. (e.key or "")
        local k = e.kind
        local desc = abbr:sub(7) .. ": " .. wire_text(e)
        if k == "group" then
            orion_fields[abbr] = ProtoField.none(abbr, e.key, desc)
            make_orion_fields(abbr, e.fields)
        elseif k == "field" or k == "bits" or k == "count" then
            if orion_fields[abbr] == nil then
                local m = e.member
                if m == "float" then
                    orion_fields[abbr] = ProtoField.double(abbr, e.key, desc)
                elseif m == "bool" then
                    orion_fields[abbr] = ProtoField.bool(abbr, e.key, base.NONE, nil, nil, desc)
                elseif m == "enum" then
                    orion_fields[abbr] = ProtoField.string(abbr, e.key, desc)
                elseif e.enc == "i" then
                    orion_fields[abbr] = ProtoField.int32(abbr, e.key, base.DEC, nil, nil, desc)
                else
                    orion_fields[abbr] = ProtoField.uint32(abbr, e.key, base.DEC, nil, nil, desc)
                end
            end
        elseif k == "string" or k == "fixed_string" then
            orion_fields[abbr] = ProtoField.string(abbr, e.key, desc)
        elseif k == "ipv4" then
            orion_fields[abbr] = ProtoField.ipv4(abbr, e.key, desc)
        end
    end
end
-- orion.<packet> itself is a field too, so `-Y orion.geolocate_telemetry` selects a packet kind.
local orion_packet_fields = {}
for _, p in pairs(orion_packets) do
    orion_packet_fields[p.name] = ProtoField.none("orion." .. p.name, p.name)
    orion_fields["orion." .. p.name] = orion_packet_fields[p.name]
    make_orion_fields("orion." .. p.name, p.fields)
end

do
    local list = {}
    for _, f in pairs(of) do list[#list + 1] = f end
    for _, f in pairs(orion_fields) do list[#list + 1] = f end
    orion_proto.fields = list
    orion_proto.experts = {
        orion_expert.bad_checksum, orion_expert.short, orion_expert.truncated,
        orion_expert.bad_sync, orion_expert.unknown, orion_expert.extra,
    }
end

-- Fletcher-16 with A starting at 1 and both sums modulo 251 (ICD "Checksum").
local function fletcher251(tvb, offset, len)
    local a, b = 1, 0
    for i = offset, offset + len - 1 do
        a = (a + tvb(i, 1):uint()) % 251
        b = (b + a) % 251
    end
    return a * 256 + b
end

local function round_half_away(x)
    if x >= 0 then return math.floor(x + 0.5) end
    return -math.floor(-x + 0.5)
end

-- F16:X (ProtoGen float16ToFloat32): only a zero magnitude is zero.
local function small_to_float(raw, total_bits, sig_bits)
    local sign_bit = 2 ^ (total_bits - 1)
    local negative = raw >= sign_bit
    local magnitude = negative and raw - sign_bit or raw
    if magnitude == 0 then return negative and -0.0 or 0.0 end
    local bias = 2 ^ (total_bits - 2 - sig_bits) - 1
    local sig_scale = 2 ^ sig_bits
    local biased_exp = math.floor(magnitude / sig_scale)
    local mantissa = magnitude % sig_scale
    local value = (mantissa + sig_scale) * 2 ^ (biased_exp - bias - sig_bits)
    return negative and -value or value
end

-- The fewest decimals that still encode to the same wire integer (contract section 1).
local function short_text(value, raw, e)
    if e.enc ~= "u" and e.enc ~= "i" then return string.format("%.9g", value) end
    local to_json = e.radians and rad2deg or 1.0
    local factor, offset = e.factor or 1.0, e.offset or 0.0
    local scale = 1.0
    for decimals = 0, 15 do
        local candidate = round_half_away(value * scale) / scale
        if round_half_away((candidate / to_json - offset) * factor) == raw then
            return string.format("%." .. decimals .. "f", candidate)
        end
        scale = scale * 10
    end
    return string.format("%.17g", value)
end

-- Decoder state over one packet's data, mirroring lib/protocols/orion/codec/codec.hpp's Decoder: whole-byte
-- fields start on a new byte after a bitfield; running out in the optional tail ends the
-- packet quietly, elsewhere it is an error.
local function new_state(tvb, offset, len)
    return { tvb = tvb, start = offset, stop = offset + len, pos = offset, bit = 0,
             optional = false, absent = false, failed = false, failed_key = nil }
end

local function align(s)
    if s.bit ~= 0 then s.bit = 0; s.pos = s.pos + 1 end
end

local function ran_out(s, key)
    if s.optional then s.absent = true else s.failed = true; s.failed_key = key end
end

local function need(s, key, n)
    if s.failed or s.absent then return false end
    align(s)
    if s.pos + n <= s.stop then return true end
    ran_out(s, key)
    return false
end

local function need_bits(s, key, width)
    if s.failed or s.absent then return false end
    local left = s.pos < s.stop and (s.stop - s.pos) * 8 - s.bit or 0
    if left >= width then return true end
    ran_out(s, key)
    return false
end

local function take_bits(s, width)
    local first = s.pos
    local raw = 0
    for _ = 1, width do
        local byte = s.tvb(s.pos, 1):uint()
        local bit = math.floor(byte / 2 ^ (7 - s.bit)) % 2
        raw = raw * 2 + bit
        s.bit = s.bit + 1
        if s.bit == 8 then s.bit = 0; s.pos = s.pos + 1 end
    end
    local last = s.bit == 0 and s.pos - 1 or s.pos
    return raw, s.tvb(first, last - first + 1)
end

local function read_raw(s, e)
    local range = s.tvb(s.pos, e.size)
    s.pos = s.pos + e.size
    if e.enc == "f32" or e.enc == "f64" then return range:float(), range end
    local raw = range:uint()
    if e.enc == "i" and raw >= 2 ^ (8 * e.size - 1) then raw = raw - 2 ^ (8 * e.size) end
    if e.enc == "sf" then return small_to_float(raw, 8 * e.size, e.sig), range end
    return raw, range
end

-- Adds one decoded item; returns the raw integer (counts and conditions use it).
local function add_value(tree, abbr, e, raw, range, label)
    local f = orion_fields[abbr]
    local m = e.member
    if m == "float" then
        local value = raw * (1.0 / (e.factor or 1.0)) + (e.offset or 0.0)
        if e.radians then value = value * rad2deg end
        local text = short_text(value, raw, e)
        local item = tree:add(f, range, value)
        item:set_text(label .. ": " .. text .. (e.radians and " deg" or ""))
    elseif m == "bool" then
        tree:add(f, range, raw ~= 0):set_text(label .. ": " .. tostring(raw ~= 0))
    elseif m == "enum" then
        local name = orion_enums[e.enum][raw]
        local value = name or tostring(raw)
        tree:add(f, range, value):set_text(label .. ": " .. value .. " (" .. raw .. ")")
    else
        tree:add(f, range, raw):set_text(label .. ": " .. raw)
    end
end

-- Printable ASCII kept, anything else '?' (the Orion codec's printable()).
local function printable(bytes)
    return (bytes:gsub("[^\32-\126]", "?"))
end

local decode_entries

local function decode_entry(s, tree, prefix, e, scope)
    local k = e.kind
    local abbr = prefix .. "." .. (e.key or "")
    if e.cond then
        local v = scope[e.cond.key] or 0
        local listed = false
        for _, x in ipairs(e.cond.values) do if x == v then listed = true end end
        if listed ~= e.cond.present then return end
    end
    if k == "optional" then
        s.optional = true
    elseif k == "reserved" then
        if need(s, "reserved", e.size) then s.pos = s.pos + e.size end
    elseif k == "reserved_bits" then
        if need_bits(s, "reserved", e.width) then take_bits(s, e.width) end
    elseif k == "bits" then
        if not need_bits(s, e.key, e.width) then return end
        local raw, range = take_bits(s, e.width)
        scope[e.key] = raw
        add_value(tree, abbr, e, raw, range, e.key)
    elseif k == "count" then
        if not need(s, e.key, e.size) then return end
        local raw, range = read_raw(s, e)
        scope[e.key] = math.min(raw, e.max)
        tree:add(orion_fields[abbr], range, raw):set_text(e.key .. ": " .. raw)
    elseif k == "field" or k == "ipv4" then
        local n = e.n
        if e.count then n = scope[e.count] or 0 end
        if n == nil then
            if not need(s, e.key, e.size) then return end
            local raw, range = read_raw(s, e)
            scope[e.key] = raw
            if k == "ipv4" then
                tree:add(orion_fields[abbr], range)
            else
                add_value(tree, abbr, e, raw, range, e.key)
            end
        else
            if not need(s, e.key, e.size * n) then return end
            local sub = tree
            if n > 4 then sub = tree:add(orion_proto, s.tvb(s.pos, e.size * n), e.key .. " [" .. n .. "]") end
            for i = 1, n do
                local raw, range = read_raw(s, e)
                add_value(sub, abbr, e, raw, range, e.key .. "[" .. (i - 1) .. "]")
            end
        end
    elseif k == "string" then
        if not need(s, e.key, 1) then return end
        local left = s.stop - s.pos
        local limit = math.min(e.max - 1, left)
        local n = 0
        while n < limit and s.tvb(s.pos + n, 1):uint() ~= 0 do n = n + 1 end
        local used = n < left and n + 1 or n
        local text = printable(s.tvb(s.pos, used):raw(0, n))
        tree:add(orion_fields[abbr], s.tvb(s.pos, used), text)
        s.pos = s.pos + used
    elseif k == "fixed_string" then
        if not need(s, e.key, e.size) then return end
        local bytes = s.tvb(s.pos, e.size):raw()
        local text = bytes:sub(1, e.size - 1)
        local zero = text:find("\0", 1, true)
        if zero then text = text:sub(1, zero - 1) end
        tree:add(orion_fields[abbr], s.tvb(s.pos, e.size), printable(text))
        s.pos = s.pos + e.size
    elseif k == "group" then
        local n = e.n
        if e.count then n = scope[e.count] or 0 end
        for i = 1, n do
            if s.failed or s.absent then return end
            local item_start = math.min(s.pos, s.stop - 1)
            local sub = tree:add(orion_fields[abbr], s.tvb(item_start, 0))
            sub:set_text(e.key .. "[" .. (i - 1) .. "]")
            local first = s.pos
            decode_entries(s, sub, abbr, e.fields, {})
            if s.pos > first then sub:set_len(s.pos - first + (s.bit > 0 and 1 or 0)) end
        end
    end
end

decode_entries = function(s, tree, prefix, entries, scope)
    for _, e in ipairs(entries) do
        if s.failed or s.absent then return end
        decode_entry(s, tree, prefix, e, scope)
    end
end

local function dissect_orion_frame(tvb, pinfo, tree, offset)
    local available = tvb:len() - offset
    if available < 6 then
        local t = tree:add(orion_proto, tvb(offset))
        t:add_proto_expert_info(orion_expert.truncated)
        return available
    end
    local id = tvb(offset + 2, 1):uint()
    local len = tvb(offset + 3, 1):uint()
    local frame_len = 6 + len
    local name = orion_id_names[id] or ("id " .. id)
    local t = tree:add(orion_proto, tvb(offset, math.min(frame_len, available)),
                       "OrionPublic " .. name)
    local sync = t:add(of.sync, tvb(offset, 2))
    if tvb(offset, 2):uint() ~= 0xD00D then sync:add_proto_expert_info(orion_expert.bad_sync) end
    t:add(of.id, tvb(offset + 2, 1))
    t:add(of.packet, tvb(offset + 2, 1), name)
    t:add(of.length, tvb(offset + 3, 1))
    if available < frame_len then
        t:add_proto_expert_info(orion_expert.truncated)
        return available
    end

    local info
    local p = orion_packets[id]
    if len == 0 then
        t:add(of.request, tvb(offset + 3, 1), true)
        info = "request " .. name
    elseif p then
        local body = t:add(orion_packet_fields[p.name], tvb(offset + 4, len))
        local s = new_state(tvb, offset + 4, len)
        decode_entries(s, body, "orion." .. p.name, p.fields, {})
        if s.failed then
            body:add_proto_expert_info(orion_expert.short,
                "Orion " .. p.name .. ": packet too short for field '" .. tostring(s.failed_key) .. "'")
        elseif not s.absent then
            align(s)
            if s.pos < s.stop then
                local extra = body:add(of.extra, tvb(s.pos, s.stop - s.pos))
                extra:add_proto_expert_info(orion_expert.extra)
            end
        end
        info = name
    else
        t:add(of.data, tvb(offset + 4, len)):add_proto_expert_info(orion_expert.unknown)
        info = name
    end

    local stated = tvb(offset + 4 + len, 2):uint()
    local computed = fletcher251(tvb, offset, 4 + len)
    t:add(of.checksum, tvb(offset + 4 + len, 2))
    local status = t:add(of.checksum_computed, tvb(offset + 4 + len, 2), computed)
    status:set_generated()
    if stated == computed then
        t:add(of.checksum_status, tvb(offset + 4 + len, 2), "good"):set_generated()
    else
        t:add(of.checksum_status, tvb(offset + 4 + len, 2), "bad"):set_generated()
        t:add_proto_expert_info(orion_expert.bad_checksum, string.format(
            "Bad Orion checksum: 0x%04x, expected 0x%04x", stated, computed))
        info = info .. " [bad checksum]"
    end
    return frame_len, info
end

function orion_proto.dissector(tvb, pinfo, tree)
    pinfo.cols.protocol = "Orion"
    local offset = 0
    local infos = {}
    while offset < tvb:len() do
        local used, info = dissect_orion_frame(tvb, pinfo, tree, offset)
        if info then infos[#infos + 1] = info end
        offset = offset + used
    end
    pinfo.cols.info = table.concat(infos, ", ")
    return tvb:len()
end

-- OrionPublic over TCP (captures of a network gimbal, not gimbald recordings): the stream is
-- cut into frames by their length byte, with TCP reassembly. Port 8747 (gimbald's examples);
-- other ports via Decode As... > TCP port > ORION-TCP.
local orion_tcp_proto = Proto("orion-tcp", "OrionPublic over TCP")

local function orion_frame_length(tvb, pinfo, offset)
    return 6 + tvb(offset + 3, 1):uint()
end

local function dissect_one_orion_frame(tvb, pinfo, tree)
    return orion_proto.dissector(tvb, pinfo, tree)
end

function orion_tcp_proto.dissector(tvb, pinfo, tree)
    dissect_tcp_pdus(tvb, tree, 4, orion_frame_length, dissect_one_orion_frame)
    return tvb:len()
end

do
    local tcp_port = DissectorTable.get("tcp.port")
    tcp_port:add(8747, orion_tcp_proto)
end

------------------------------------------------------------------------------------------------
-- Viewpro (lib/protocols/viewpro/codec; contract section 7 errata: OUT3/OUT4 share FD and 60
-- bytes, IN2/IN3 share FC and 40 bytes, byte 3 = FF marks OUT4 / IN3). Little-endian; the
-- checksum is the sum of all previous bytes mod 256; the 5-byte commands AA 55 id xx FF have
-- none.
------------------------------------------------------------------------------------------------

local viewpro_proto = Proto("viewpro", "Viewpro target GPS protocol")

local vf = {
    frame = ProtoField.string("viewpro.frame", "Frame"),
    header = ProtoField.uint16("viewpro.header", "Header", base.HEX),
    id = ProtoField.uint8("viewpro.id", "Id", base.HEX),
    flag = ProtoField.uint8("viewpro.flag", "OUT4/IN3 flag", base.HEX),
    checksum = ProtoField.uint8("viewpro.checksum", "Checksum", base.HEX),
    checksum_computed = ProtoField.uint8("viewpro.checksum.computed", "Computed checksum", base.HEX),
    checksum_status = ProtoField.string("viewpro.checksum.status", "Checksum status"),
    ["end"] = ProtoField.uint8("viewpro.end", "End", base.HEX),
    time = ProtoField.string("viewpro.time", "time"),
    zoom = ProtoField.uint16("viewpro.zoom", "zoom"),
    osd = ProtoField.string("viewpro.osd", "osd"),
    network = ProtoField.bool("viewpro.network", "network"),
    serial = ProtoField.bool("viewpro.serial", "serial"),
    format = ProtoField.string("viewpro.format", "format"),
    hundredths_deg = ProtoField.int8("viewpro.hundredths_deg", "hundredths_deg"),
}
-- Every number in contract units (degrees, metres, m/s).
for _, name in ipairs({ "gimbal.roll", "gimbal.pitch", "gimbal.yaw", "lrf_m", "uav.roll",
                        "uav.pitch", "uav.yaw", "uav.lat", "uav.lon", "uav.alt_msl",
                        "target.lat", "target.lon", "target.alt_msl", "roll", "pitch", "yaw",
                        "lat", "lon", "alt_msl", "vel_ned", "deg" }) do
    vf[name] = ProtoField.double("viewpro." .. name, name)
end
local viewpro_expert = {
    bad_checksum = ProtoExpert.new("viewpro.checksum.bad", "Bad Viewpro checksum",
                                   expert.group.CHECKSUM, expert.severity.WARN),
    unknown = ProtoExpert.new("viewpro.unknown", "Not a complete Viewpro frame",
                              expert.group.MALFORMED, expert.severity.ERROR),
}
do
    local list = {}
    for _, f in pairs(vf) do list[#list + 1] = f end
    viewpro_proto.fields = list
    viewpro_proto.experts = { viewpro_expert.bad_checksum, viewpro_expert.unknown }
end

-- Field readers: {field, offset, reader}; a reader returns (value, length).
local function f32(o) return function(t) return t(o, 4):le_float(), 4 end end
local function f32_rad(o) return function(t) return t(o, 4):le_float() * rad2deg, 4 end end
local function f64_rad(o) return function(t) return t(o, 8):le_float() * rad2deg, 8 end end
local function i32_div(o, d) return function(t) return t(o, 4):le_int() / d, 4 end end
local function u32_div(o, d) return function(t) return t(o, 4):le_uint() / d, 4 end end
local function i16_div(o, d) return function(t) return t(o, 2):le_int() / d, 2 end end

local common_out23 = {
    { "zoom", 9, function(t) return t(9, 2):le_uint(), 2 end },
    { "gimbal.roll", 11, f32_rad(11) }, { "gimbal.pitch", 15, f32_rad(15) },
    { "gimbal.yaw", 19, f32_rad(19) }, { "lrf_m", 23, f32(23) },
    { "uav.roll", 27, f32_rad(27) }, { "uav.pitch", 31, f32_rad(31) },
    { "uav.yaw", 35, f32_rad(35) }, { "uav.alt_msl", 39, i32_div(39, 1e3) },
}
local lat_lon_e7 = {
    { "uav.lat", 43, i32_div(43, 1e7) }, { "uav.lon", 47, i32_div(47, 1e7) },
    { "target.lat", 51, i32_div(51, 1e7) }, { "target.lon", 55, i32_div(55, 1e7) },
}
local function concat(...)
    local out = {}
    for _, list in ipairs({ ... }) do for _, x in ipairs(list) do out[#out + 1] = x end end
    return out
end
local velocity = {
    { "vel_ned", 33, i16_div(33, 100) }, { "vel_ned", 35, i16_div(35, 100) },
    { "vel_ned", 37, i16_div(37, 100) },
}
local position = {
    { "lat", 21, i32_div(21, 1e7) }, { "lon", 25, i32_div(25, 1e7) },
    { "alt_msl", 29, i32_div(29, 1e3) },
}
local vehicle_attitude = {
    { "roll", 9, f32_rad(9) }, { "pitch", 13, f32_rad(13) }, { "yaw", 17, f32_rad(17) },
}

-- year = "u16": bytes 2..3 hold the year; "u8+2000": byte 2 holds year - 2000 (OUT4, IN3).
local viewpro_frames = {
    out1 = { size = 23, fields = {
        { "gimbal.pitch", 2, f32(2) }, { "gimbal.yaw", 6, f32(6) }, { "lrf_m", 10, f32(10) },
        { "target.lon", 14, i32_div(14, 1e7) }, { "target.lat", 18, i32_div(18, 1e7) } } },
    out2 = { size = 76, year = "u16", fields = concat(common_out23, {
        { "uav.lat", 43, f64_rad(43) }, { "uav.lon", 51, f64_rad(51) },
        { "target.lat", 59, f64_rad(59) }, { "target.lon", 67, f64_rad(67) } }) },
    out3 = { size = 60, year = "u16", fields = concat(common_out23, lat_lon_e7) },
    out4 = { size = 60, year = "u8+2000", fields = concat({
        { "zoom", 9, function(t) return t(9, 2):le_uint(), 2 end },
        { "gimbal.roll", 11, i32_div(11, 1e3) }, { "gimbal.pitch", 15, i32_div(15, 1e3) },
        { "gimbal.yaw", 19, i32_div(19, 1e3) }, { "lrf_m", 23, u32_div(23, 1e3) },
        { "target.alt_msl", 27, i32_div(27, 1e3) }, { "uav.pitch", 31, i32_div(31, 1e3) },
        { "uav.yaw", 35, i32_div(35, 1e3) }, { "uav.alt_msl", 39, i32_div(39, 1e3) } },
        lat_lon_e7) },
    in1 = { size = 34, year = "u16", fields = concat(vehicle_attitude, position) },
    in2 = { size = 40, year = "u16", fields = concat(vehicle_attitude, position, velocity) },
    in3 = { size = 40, year = "u8+2000", fields = concat({
        { "lrf_m", 9, u32_div(9, 1e3) }, { "pitch", 13, i32_div(13, 1e3) },
        { "yaw", 17, i32_div(17, 1e3) } }, position, velocity) },
}

local function viewpro_kind(tvb)
    local len = tvb:len()
    if len < 2 then return nil end
    local h, id = tvb(0, 1):uint(), tvb(1, 1):uint()
    local flag = len > 3 and tvb(3, 1):uint() or 0
    if h == 0xAA and id == 0x55 and len == 5 then
        local cmd = tvb(2, 1):uint()
        if cmd == 0x0F then return "mode" end
        if cmd == 0x06 then return "yaw_shift" end
        if cmd == 0x36 then return "pitch_shift" end
        return nil
    end
    if h == 0xFE then
        if id == 0xFB then return "out1" end
        if id == 0xFC then return "out2" end
        if id == 0xFD then return flag == 0xFF and "out4" or "out3" end
    elseif h == 0xF9 then
        if id == 0xFB then return "in1" end
        if id == 0xFC then return flag == 0xFF and "in3" or "in2" end
    end
    return nil
end

local function add_number(tree, name, range, value)
    tree:add(vf[name], range, value):set_text(name .. ": " .. string.format("%.10g", value))
end

local format_names = { [0] = "out1", [1] = "out2", [2] = "out3", [3] = "out4" }

function viewpro_proto.dissector(tvb, pinfo, tree)
    pinfo.cols.protocol = "Viewpro"
    local kind = viewpro_kind(tvb)
    local t = tree:add(viewpro_proto, tvb(), "Viewpro " .. (kind or "?"))
    local layout = kind and viewpro_frames[kind]
    if not kind or (layout and tvb:len() ~= layout.size) then
        t:add_proto_expert_info(viewpro_expert.unknown)
        pinfo.cols.info = "Viewpro: not a complete frame"
        return tvb:len()
    end
    t:add(vf.frame, tvb(0, 2), kind)
    t:add(vf.header, tvb(0, 2))
    pinfo.cols.info = kind

    if not layout then  -- a 5-byte command: AA 55 id value FF
        t:add(vf.id, tvb(2, 1))
        local v = tvb(3, 1)
        if kind == "mode" then
            local b = v:uint()
            t:add(vf.osd, v, b % 2 == 1 and "target" or "uav")
            t:add(vf.network, v, math.floor(b / 8) % 2 == 1)
            t:add(vf.serial, v, math.floor(b / 16) % 2 == 1)
            t:add(vf.format, v, format_names[math.floor(b / 32) % 4])
        else
            t:add(vf.hundredths_deg, v, v:int())
            add_number(t, "deg", v, v:int() / 100.0)
        end
        t:add(vf["end"], tvb(4, 1))
        return tvb:len()
    end

    t:add(vf.id, tvb(1, 1))
    if kind:sub(1, 3) == "out" then t:add(vf.format, tvb(1, 1), kind) end
    if layout.year then
        local year, year_range
        if layout.year == "u16" then
            year, year_range = tvb(2, 2):le_uint(), tvb(2, 2)
        else
            year, year_range = 2000 + tvb(2, 1):uint(), tvb(2, 1)
            t:add(vf.flag, tvb(3, 1))
        end
        local time = string.format("%04d-%02d-%02dT%02d:%02d:%02dZ", year, tvb(4, 1):uint(),
                                   tvb(5, 1):uint(), tvb(6, 1):uint(), tvb(7, 1):uint(),
                                   tvb(8, 1):uint())
        t:add(vf.time, tvb(2, 7), time)
    end
    for _, f in ipairs(layout.fields) do
        local value, len = f[3](tvb)
        if f[1] == "zoom" then
            t:add(vf.zoom, tvb(f[2], len), value)
        else
            add_number(t, f[1], tvb(f[2], len), value)
        end
    end
    local last = layout.size - 1
    local sum = 0
    for i = 0, last - 1 do sum = (sum + tvb(i, 1):uint()) % 256 end
    t:add(vf.checksum, tvb(last, 1))
    t:add(vf.checksum_computed, tvb(last, 1), sum):set_generated()
    if tvb(last, 1):uint() == sum then
        t:add(vf.checksum_status, tvb(last, 1), "good"):set_generated()
    else
        t:add(vf.checksum_status, tvb(last, 1), "bad"):set_generated()
        t:add_proto_expert_info(viewpro_expert.bad_checksum, string.format(
            "Bad Viewpro checksum: 0x%02x, expected 0x%02x", tvb(last, 1):uint(), sum))
        pinfo.cols.info = kind .. " [bad checksum]"
    end
    return tvb:len()
end

------------------------------------------------------------------------------------------------
-- MAVLink v1/v2: header, message id and name, CRC (X.25 with crc_extra) for the messages
-- gimbald uses (lib/mavlink; the dissector test checks this table against it).
------------------------------------------------------------------------------------------------

local mavlink_messages = {
    [0] = { "HEARTBEAT", 50 }, [2] = { "SYSTEM_TIME", 137 }, [30] = { "ATTITUDE", 39 },
    [33] = { "GLOBAL_POSITION_INT", 104 }, [65] = { "RC_CHANNELS", 118 },
    [75] = { "COMMAND_INT", 158 }, [76] = { "COMMAND_LONG", 152 }, [77] = { "COMMAND_ACK", 143 },
    [259] = { "CAMERA_INFORMATION", 92 }, [260] = { "CAMERA_SETTINGS", 146 },
    [261] = { "STORAGE_INFORMATION", 179 }, [262] = { "CAMERA_CAPTURE_STATUS", 12 },
    [269] = { "VIDEO_STREAM_INFORMATION", 109 }, [270] = { "VIDEO_STREAM_STATUS", 59 },
    [271] = { "CAMERA_FOV_STATUS", 22 }, [275] = { "CAMERA_TRACKING_IMAGE_STATUS", 126 },
    [276] = { "CAMERA_TRACKING_GEO_STATUS", 18 },
    [280] = { "GIMBAL_MANAGER_INFORMATION", 70 }, [281] = { "GIMBAL_MANAGER_STATUS", 48 },
    [282] = { "GIMBAL_MANAGER_SET_ATTITUDE", 123 }, [283] = { "GIMBAL_DEVICE_INFORMATION", 74 },
    [284] = { "GIMBAL_DEVICE_SET_ATTITUDE", 99 }, [285] = { "GIMBAL_DEVICE_ATTITUDE_STATUS", 137 },
    [286] = { "AUTOPILOT_STATE_FOR_GIMBAL_DEVICE", 210 }, [287] = { "GIMBAL_MANAGER_SET_PITCHYAW", 1 },
}

-- The payload fields of the gimbal device messages (common.xml), in wire order (MAVLink 2:
-- base fields by type size, then extensions): { name, type, count }. A v2 payload may be
-- truncated; the fields are read from it zero-extended.
local mavlink_payload_fields = {
    [283] = { { "uid", "u64" }, { "time_boot_ms", "u32" }, { "firmware_version", "u32" },
              { "hardware_version", "u32" }, { "roll_min", "f32" }, { "roll_max", "f32" },
              { "pitch_min", "f32" }, { "pitch_max", "f32" }, { "yaw_min", "f32" },
              { "yaw_max", "f32" }, { "cap_flags", "u16" }, { "custom_cap_flags", "u16" },
              { "vendor_name", "str", 32 }, { "model_name", "str", 32 },
              { "custom_name", "str", 32 }, { "gimbal_device_id", "u8" }, { "cap_flags2", "u32" } },
    [284] = { { "q", "f32", 4 }, { "angular_velocity_x", "f32" }, { "angular_velocity_y", "f32" },
              { "angular_velocity_z", "f32" }, { "flags", "u16" }, { "target_system", "u8" },
              { "target_component", "u8" } },
    [285] = { { "time_boot_ms", "u32" }, { "q", "f32", 4 }, { "angular_velocity_x", "f32" },
              { "angular_velocity_y", "f32" }, { "angular_velocity_z", "f32" },
              { "failure_flags", "u32" }, { "flags", "u16" }, { "target_system", "u8" },
              { "target_component", "u8" }, { "delta_yaw", "f32" },
              { "delta_yaw_velocity", "f32" }, { "gimbal_device_id", "u8" } },
    [286] = { { "time_boot_us", "u64" }, { "q", "f32", 4 }, { "q_estimated_delay_us", "u32" },
              { "vx", "f32" }, { "vy", "f32" }, { "vz", "f32" }, { "v_estimated_delay_us", "u32" },
              { "feed_forward_angular_velocity_z", "f32" }, { "estimator_status", "u16" },
              { "target_system", "u8" }, { "target_component", "u8" }, { "landed_state", "u8" },
              { "angular_velocity_z", "f32" } },
}
local mavlink_type_size = { u64 = 8, u32 = 4, f32 = 4, u16 = 2, u8 = 1, str = 1 }

local mavlink_proto = Proto("mavlink", "MAVLink (gimbald)")
local mf = {
    magic = ProtoField.uint8("mavlink.magic", "Magic", base.HEX),
    version = ProtoField.uint8("mavlink.version", "Version"),
    len = ProtoField.uint8("mavlink.len", "Payload length"),
    incompat_flags = ProtoField.uint8("mavlink.incompat_flags", "Incompatibility flags", base.HEX),
    compat_flags = ProtoField.uint8("mavlink.compat_flags", "Compatibility flags", base.HEX),
    seq = ProtoField.uint8("mavlink.seq", "Sequence"),
    sysid = ProtoField.uint8("mavlink.sysid", "System id"),
    compid = ProtoField.uint8("mavlink.compid", "Component id"),
    msgid = ProtoField.uint32("mavlink.msgid", "Message id"),
    msgname = ProtoField.string("mavlink.msgname", "Message"),
    payload = ProtoField.bytes("mavlink.payload", "Payload"),
    crc = ProtoField.uint16("mavlink.crc", "CRC", base.HEX),
    crc_status = ProtoField.string("mavlink.crc.status", "CRC status"),
    signature = ProtoField.bytes("mavlink.signature", "Signature"),
}
-- One ProtoField per payload field name of mavlink_payload_fields: mavlink.<name>.
local mavlink_field_of = {}
for _, fields in pairs(mavlink_payload_fields) do
    for _, f in ipairs(fields) do
        local name, kind = f[1], f[2]
        if not mavlink_field_of[name] then
            local abbr = "mavlink." .. name
            local field
            if kind == "f32" then
                field = ProtoField.float(abbr, name)
            elseif kind == "u64" then
                field = ProtoField.uint64(abbr, name)
            elseif kind == "str" then
                field = ProtoField.string(abbr, name)
            elseif kind == "u32" then
                field = ProtoField.uint32(abbr, name)
            elseif kind == "u16" then
                field = ProtoField.uint16(abbr, name, base.DEC)
            else
                field = ProtoField.uint8(abbr, name)
            end
            mavlink_field_of[name] = field
            mf["payload_" .. name] = field
        end
    end
end
local mavlink_expert = {
    bad_crc = ProtoExpert.new("mavlink.crc.bad", "Bad MAVLink CRC", expert.group.CHECKSUM,
                              expert.severity.WARN),
    short = ProtoExpert.new("mavlink.short", "MAVLink frame shorter than its header says",
                            expert.group.MALFORMED, expert.severity.ERROR),
}
do
    local list = {}
    for _, f in pairs(mf) do list[#list + 1] = f end
    mavlink_proto.fields = list
    mavlink_proto.experts = { mavlink_expert.bad_crc, mavlink_expert.short }
end

local function x25(crc, byte)
    local tmp = bit32.bxor(byte, bit32.band(crc, 0xFF))
    tmp = bit32.band(bit32.bxor(tmp, bit32.lshift(tmp, 4)), 0xFF)
    return bit32.band(bit32.bxor(bit32.rshift(crc, 8), bit32.lshift(tmp, 8),
                                 bit32.lshift(tmp, 3), bit32.rshift(tmp, 4)), 0xFFFF)
end

function mavlink_proto.dissector(tvb, pinfo, tree)
    pinfo.cols.protocol = "MAVLink"
    local t = tree:add(mavlink_proto, tvb())
    local magic = tvb:len() > 0 and tvb(0, 1):uint() or 0
    local v2 = magic == 0xFD
    local header = v2 and 10 or 6
    if tvb:len() < header + 2 or (magic ~= 0xFD and magic ~= 0xFE) then
        t:add_proto_expert_info(mavlink_expert.short)
        return tvb:len()
    end
    local len = tvb(1, 1):uint()
    t:add(mf.magic, tvb(0, 1))
    t:add(mf.version, tvb(0, 1), v2 and 2 or 1)
    t:add(mf.len, tvb(1, 1))
    local o = 2
    local signed = false
    if v2 then
        t:add(mf.incompat_flags, tvb(2, 1))
        t:add(mf.compat_flags, tvb(3, 1))
        signed = tvb(2, 1):uint() % 2 == 1
        o = 4
    end
    t:add(mf.seq, tvb(o, 1))
    t:add(mf.sysid, tvb(o + 1, 1))
    t:add(mf.compid, tvb(o + 2, 1))
    local msgid = v2 and tvb(o + 3, 3):le_uint() or tvb(o + 3, 1):uint()
    t:add(mf.msgid, tvb(o + 3, v2 and 3 or 1), msgid)
    local info = mavlink_messages[msgid]
    local name = info and info[1] or ("MSG " .. msgid)
    t:add(mf.msgname, tvb(o + 3, v2 and 3 or 1), name)
    t:append_text(", " .. name)
    pinfo.cols.info = name
    if tvb:len() < header + len + 2 then
        t:add_proto_expert_info(mavlink_expert.short)
        return tvb:len()
    end
    if len > 0 then t:add(mf.payload, tvb(header, len)) end
    local layout = mavlink_payload_fields[msgid]
    if layout and len > 0 then
        -- Zero-extended to the full length: a truncated v2 payload's missing bytes are 0.
        local size = 0
        for _, f in ipairs(layout) do size = size + mavlink_type_size[f[2]] * (f[3] or 1) end
        local bytes = tvb(header, len):bytes()
        if len < size then
            bytes:set_size(size)
            for i = len, size - 1 do bytes:set_index(i, 0) end
        end
        local ptvb = len < size and bytes:tvb("MAVLink payload (zero-extended)") or tvb(header, len):tvb()
        local pt = t:add(mavlink_proto, ptvb(), "Payload fields")
        local at = 0
        for _, f in ipairs(layout) do
            local name, kind, count = f[1], f[2], f[3] or 1
            local width = mavlink_type_size[kind]
            if kind == "str" then
                pt:add(mavlink_field_of[name], ptvb(at, count), ptvb(at, count):stringz())
                at = at + count
            else
                for _ = 1, count do
                    if at + width > ptvb:len() then break end
                    pt:add_le(mavlink_field_of[name], ptvb(at, width))
                    at = at + width
                end
            end
        end
    end
    local crc_range = tvb(header + len, 2)
    t:add_le(mf.crc, crc_range)
    if info then
        local crc = 0xFFFF
        for i = 1, header + len - 1 do crc = x25(crc, tvb(i, 1):uint()) end
        crc = x25(crc, info[2])
        if crc == crc_range:le_uint() then
            t:add(mf.crc_status, crc_range, "good"):set_generated()
        else
            t:add(mf.crc_status, crc_range, "bad"):set_generated()
            t:add_proto_expert_info(mavlink_expert.bad_crc, string.format(
                "Bad MAVLink CRC: 0x%04x, expected 0x%04x", crc_range:le_uint(), crc))
        end
    end
    if signed and tvb:len() >= header + len + 2 + 13 then
        t:add(mf.signature, tvb(header + len + 2, 13))
    end
    return tvb:len()
end

------------------------------------------------------------------------------------------------
-- gimbald-json: JSON requests (inbound) and replies (outbound) of every transport, shown by
-- Wireshark's json dissector (filters json.member etc.); on a `track:<gimbal>` interface, the
-- visual track's records (events and STATE track, docs/recording-format.md).
------------------------------------------------------------------------------------------------

local json_proto = Proto("gimbald-json", "gimbald JSON")
local jf = { text = ProtoField.string("gimbald-json.text", "Text") }
json_proto.fields = { jf.text }
local json_dissector = Dissector.get("json")
local interface_name = Field.new("frame.interface_name")

-- "track_lost id 3" or "track 3 tracking, confidence 0.93, 45.6973012 -121.4807403".
local function track_summary(text)
    local id = text:match('"id":(%d+)') or "?"
    local event = text:match('"event":"([%w_]+)"')
    if event then
        local reason = text:match('"reason":"([%w_]+)"')
        return event .. " id " .. id .. (reason and (" (" .. reason .. ")") or "")
    end
    local summary = "track " .. id .. " " .. (text:match('"state":"(%a+)"') or "?")
    local confidence = text:match('"confidence":([-%d.e]+)')
    if confidence then summary = summary .. ", confidence " .. confidence end
    local lat, lon = text:match('"lat":([-%d.e]+)'), text:match('"lon":([-%d.e]+)')
    if lat and lon then summary = summary .. ", " .. lat .. " " .. lon end
    return summary
end

function json_proto.dissector(tvb, pinfo, tree)
    local t = tree:add(json_proto, tvb())
    local itf = interface_name()
    local track = itf ~= nil and tostring(itf.value):sub(1, 6) == "track:"
    local request = pinfo.p2p_dir == P2P_DIR_RECV
    t:append_text(track and " (track record)" or request and " (request)" or " (reply)")
    json_dissector:call(tvb, pinfo, tree)
    pinfo.cols.protocol = "gimbald-json"
    if track then
        local ok, text = pcall(function() return tvb():string() end)
        if ok then pinfo.cols.info = track_summary(text) end
        return tvb:len()
    end
    local ok, first = pcall(function() return tvb(0, math.min(tvb:len(), 80)):string() end)
    if ok then pinfo.cols.info = (request and "request " or "reply ") .. first:gsub("[\r\n]", " ") end
    return tvb:len()
end
