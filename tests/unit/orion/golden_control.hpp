// Golden byte vectors of the control packets, written by hand from the ICD tables (one comment
// per field). Shared by the unit tests (tests/unit/orion/test_packets_control.cpp) and the
// dissector test (tests/dissector/), which decodes every vector with the codec and with
// dissectors/gimbald.lua and compares.
#pragma once

#include "golden_vector.hpp"

namespace gimbal::orion::golden_vectors {

const Bytes cmd_bytes{
    0x05, 0xDC,  // 0..1  Target[pan]   1500 -> 1.5 rad
    0xFF, 0x06,  // 2..3  Target[tilt]  -250 -> -0.25 rad
    0x10,        // 4     Mode          16 = ORION_MODE_RATE
    0x01,        // 5     Stabilized    1
    0x19,        // 6     ImpulseTime   25 -> 2.5 s
};

const Bytes startup_cmd_bytes{
    0x01, 0xF4,  // 0..1  Target[pan]   500 -> 0.5 rad
    0xFC, 0x18,  // 2..3  Target[tilt]  -1000 -> -1.0 rad
    0x50,        // 4     Mode          80 = ORION_MODE_POSITION
    0x01,        // 5     Stabilized    1
    0x03,        // 6     ImpulseTime   3 -> 0.3 s
};

const Bytes geopoint_bytes{
    0x1A, 0xD2, 0x74, 0x80,  // 0..3   targetLat      450000000 -> 45 deg
    0xB6, 0xFB, 0xFB, 0xC0,  // 4..7   targetLon      -1225000000 -> -122.5 deg
    0x00, 0x12, 0xD6, 0x87,  // 8..11  targetAlt      1234567 -> 123.4567 m
    0x00, 0x96,              // 12..13 targetVelNED N 150 -> 1.5 m/s
    0xFF, 0x1F,              // 14..15 targetVelNED E -225 -> -2.25 m/s
    0x00, 0x32,              // 16..17 targetVelNED D 50 -> 0.5 m/s
    0x01, 0xF4,              // 18..19 joystickRange  500 m
    0x03,                    // 20     options        3 = geopointStareClosure
};

const Bytes path_bytes{
    0x02,              // 0      numPoints            2
    0x83,              // 1      pointDown 1 | reserved 000 | numCrossTrackSteps 0011
    0xD9, 0xDA, 0x60,  // 2..4   Point[0].posEcef X   -2500000 m
    0xC2, 0xF7, 0x00,  // 5..7   Point[0].posEcef Y   -4000000 m
    0x40, 0x16, 0x40,  // 8..10  Point[0].posEcef Z   4200000 m
    0x0F, 0x42, 0x40,  // 11..13 Point[1].posEcef X   1000000 m
    0xD2, 0x39, 0x40,  // 14..16 Point[1].posEcef Y   -3000000 m
    0x4C, 0x4B, 0x40,  // 17..19 Point[1].posEcef Z   5000000 m
    0x10, 0x00,        // 20..21 alongTrackStepAngle  4096 -> 4096 pi/65535 rad
    0x96,              // 22     crossTrackStepRatio  150 -> 1.5
};

const Bytes stare_ack_bytes{
    0x12, 0x34, 0x56, 0x78,  // 0..3 echoSystemTime 0x12345678 ms
};

const Bytes camera_switch_bytes{
    0x02,  // 0 Index 2
};

const Bytes camera_state_bytes{
    0x00, 0xFA,  // 0..1 Zoom   250 -> 2.5
    0xEC, 0x78,  // 2..3 Focus  -5000 -> -0.5
    0x01,        // 4    Index  1
};

const Bytes flir_bytes{
    0x01,  // 0   Index            1
    0x57,  // 1   Reserved 0 | Palette 101 | NucType 011 (ssn_medium) | BlackHot 1
    0xC8,  // 2   MaxAgcGain       200
    0xFD,  // 3   AceLevel         -3
    0x11,  // 4   DdeThreshold     17
    0x64,  // 5   AgcMidpoint      100
    0x7B,  // 6   IntegrationTime  123 -> 123 x 29/255 + 1 ms
};

const Bytes aptina_bytes{
    0x02,        // 0      Index        2
    0x01, 0x00,  // 1..2   MinExposure  256 -> 256 x 32.95/65535 + 0.05 ms
    0x80, 0x00,  // 3..4   MaxExposure  32768 -> 32768 x 32.95/65535 + 0.05 ms
    0x08, 0x00,  // 5..6   MinGain      2048 -> 2048 x 31/65535 + 1
    0xF0, 0x00,  // 7..8   MaxGain      61440 -> 61440 x 31/65535 + 1
    0xFB,        // 9      Brightness   -5
    0x40,        // 10     Contrast     64 -> 64/127
    0xC0,        // 11     Saturation   -64 -> -64/127
    0x33,        // 12     Sharpness    51 -> 1.0
    0x80,        // 13:7   DebugEnable  1 (13:6..13:0 unused)
    0xF9,        // 14     Hue          -7
};

const Bytes zafiro_bytes{
    0x03,  // 0 Index               3
    0x01,  // 1 BlackHot            1
    0x40,  // 2 IntegrationTime     64 -> 64 x 29/255 + 1 ms
    0x01,  // 3 LapEnabled          1
    0x80,  // 4 LapGain             128 -> 128 x 3.5/255 + 0.5
    0x33,  // 5 AgcSaturation       51 -> 0.02
    0x01,  // 6 UseNucTablePresets  1
};

const Bytes hitachi_bytes{
    0x04,        // 0    Index            4
    0xFC, 0x18,  // 1..2 IntegrationTime  -1000 us
    0x00, 0x38,  // 3..4 Aperture         56 -> f/5.6
    0x66,        // 5    Sharpness        102 -> 2.0
};

const Bytes sony_bytes{
    0x05,        // 0    Index        5
    0x00, 0x10,  // 1..2 MinExposure  16 -> 16 x 32.95/65535 + 0.05 ms
    0x40, 0x00,  // 3..4 MaxExposure  16384 -> 16384 x 32.95/65535 + 0.05 ms
    0x03,        // 5    MinGain      3 dB
    0x28,        // 6    MaxGain      40 dB
    0x80,        // 7    Brightness   128
    0x7F,        // 8    Contrast     127 -> 1.0
    0x81,        // 9    Saturation   -127 -> -1.0
    0x33,        // 10   Sharpness    51 -> 1.0
    0xFF,        // 11   FrameRate    255 -> 30 Hz
};

const Bytes ktnc_bytes{
    0x06,        // 0    Index            6
    0xFE, 0x0C,  // 1..2 IntegrationTime  -500 us
    0xFF, 0xF6,  // 3..4 Aperture         -10 -> -1.0 (aperture priority off)
    0x10,        // 5    Sharpness        16 -> 16 x 16/255
    0x01,        // 6    VerticalFlip     1
    0x20,        // 7    ExposureComp     32 -> 32 x 14/255
    0x30,        // 8    Contrast         48 -> 48 x 32/255
    0x70,        // 9    Saturation       112 -> 112 x 32/255
    0xC0,        // 10   NightMode 1 | ResetToDefaults 1 | 6 bits unused
};

const Bytes retract_bytes{
    0x02,  // 0 Cmd       2 = RETRACT_CMD_RETRACT
    0x00,  // 1 Reserved  0
};

const Bytes user_data_bytes{
    0x08,                    // 0     port  8 = USER_DATA_PORT_FP3
    0x03,                    // 1     size  3
    0xDE, 0xAD, 0xBE, 0xEF,  // 2..5  id    0xDEADBEEF
    0x01, 0x02, 0x03,        // 6..8  data  01 02 03
};

const Bytes laser_cmd_bytes{
    0x00, 0x00,              // 0..1   Reserved      0
    0x01,                    // 2      Index         1
    0x61, 0x62, 0x63, 0x00,  // 3..6   Password      "abc\0"
    0x01,                    // 7      Enable        1
    0x01,                    // 8      Arm           1
    0x01,                    // 9      Fire          1
    0x00, 0x64,              // 10..11 OnTime        100 ms
    0x00, 0xC8,              // 12..13 OffTime       200 ms
    0x04, 0xD2,              // 14..15 PrfCode       1234
    0x01,                    // 16     SafetyBypass  1
};

const Bytes laser_states_bytes{
    0x02,        // 0     NumLasers                   2
    0x03,        // 1     State[0].Type               3 = LASER_TYPE_LIGHTWARE
    0xFF,        // 2     State[0] Enabled..ApFlyingLock, all 1
    0xC0,        // 3     State[0] BypassEnabled 1 | PitchAngleLock 1 | reserved 0
    0x00,        // 4     State[0] reserved 0
    0x0B, 0xB8,  // 5..6  State[0].WaitTimer          3000 ms
    0x01,        // 7     State[1].Type               1 = LASER_TYPE_POINTER
    0xAA,        // 8     State[1] 1 0 1 0 1 0 1 0 (Enabled, Active, AltitudeLock, ApCommLock)
    0x40,        // 9     State[1] BypassEnabled 0 | PitchAngleLock 1 | reserved 0
    0x00,        // 10    State[1] reserved 0
    0x00, 0x01,  // 11..12 State[1].WaitTimer         1 ms
};

inline const std::vector<GoldenVector> control_vectors{
    {pkt::cmd, "cmd", &cmd_bytes},
    {pkt::startup_cmd, "startup_cmd", &startup_cmd_bytes},
    {pkt::geopoint_cmd, "geopoint_cmd", &geopoint_bytes},
    {pkt::path, "path", &path_bytes},
    {pkt::stare_ack, "stare_ack", &stare_ack_bytes},
    {pkt::camera_switch, "camera_switch", &camera_switch_bytes},
    {pkt::camera_state, "camera_state", &camera_state_bytes},
    {pkt::flir_settings, "flir_settings", &flir_bytes},
    {pkt::aptina_settings, "aptina_settings", &aptina_bytes},
    {pkt::zafiro_settings, "zafiro_settings", &zafiro_bytes},
    {pkt::hitachi_settings, "hitachi_settings", &hitachi_bytes},
    {pkt::sony_settings, "sony_settings", &sony_bytes},
    {pkt::ktnc_settings, "ktnc_settings", &ktnc_bytes},
    {pkt::retract_cmd, "retract_cmd", &retract_bytes},
    {pkt::user_data, "user_data", &user_data_bytes},
    {pkt::laser_cmd, "laser_cmd", &laser_cmd_bytes},
    {pkt::laser_states, "laser_states", &laser_states_bytes},
};

}  // namespace gimbal::orion::golden_vectors
