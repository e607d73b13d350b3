// Golden byte vectors of the telemetry packets, written by hand from the ICD tables (one comment
// per field). Shared by the unit tests (tests/unit/orion/test_packets_telemetry.cpp) and the
// dissector test (tests/dissector/), which decodes every vector with the codec and with
// dissectors/gimbald.lua and compares.
#pragma once

#include "golden_vector.hpp"

namespace gimbal::orion::golden_vectors {

const Bytes geolocate_golden{
    0x00, 0x01, 0x23, 0x45,  //  0 systemTime 74565 ms
    0x1D, 0xCD, 0x65, 0x00,  //  4 gpsITOW 500000000 ms
    0x08, 0x98,              //  8 gpsWeek 2200
    0xE0, 0x00,              // 10 geoidUndulation -8192 -> -8192 x 120/32767 m
    0x1B, 0x3D, 0x44, 0x40,  // 12 posLat 457000000 -> 45.7 deg
    0xB7, 0x94, 0x92, 0x40,  // 16 posLon -1215000000 -> -121.5 deg
    0x00, 0xBC, 0x61, 0x4E,  // 20 posAlt 12345678 -> 1234.5678 m
    0x04, 0xD2,              // 24 velNED[0] 1234 -> 12.34 m/s
    0xFD, 0xC9,              // 26 velNED[1] -567 -> -5.67 m/s
    0x00, 0x59,              // 28 velNED[2] 89 -> 0.89 m/s
    0x40, 0x00,              // 30 gimbalQuat[0] 16384/32767
    0xC0, 0x00,              // 32 gimbalQuat[1] -16384/32767
    0x20, 0x00,              // 34 gimbalQuat[2] 8192/32767
    0x7F, 0xFF,              // 36 gimbalQuat[3] 32767 -> 1.0
    0x40, 0x00,              // 38 pan 16384 x pi/32767 rad
    0xE0, 0x00,              // 40 tilt -8192 x pi/32767 rad
    0x10, 0x00,              // 42 hfov 4096 x 2pi/65535 rad
    0x0C, 0x00,              // 44 vfov 3072 x 2pi/65535 rad
    0x00, 0x64,              // 46 losECEF[0] 100 m            (optional from here)
    0xFF, 0x38,              // 48 losECEF[1] -200 m
    0x01, 0x2C,              // 50 losECEF[2] 300 m
    0x07, 0x80,              // 52 pixelWidth 1920
    0x04, 0x38,              // 54 pixelHeight 1080
    0x70,                    // 56 mode ORION_MODE_PATH (112)
    0x80,                    // 57 pathProgress 128/255
    0x96,                    // 58 stareTime 150 -> 1.5 s
    0x03,                    // 59 pathFrom 3
    0x04,                    // 60 pathTo 4
    0x00, 0x00, 0x04, 0xD2,  // 61 imageShifts[0] 1234 -> 0.001234 rad
    0xFF, 0xFF, 0xFD, 0xC9,  // 65 imageShifts[1] -567 -> -0.000567 rad
    0x00, 0x21,              // 69 imageShiftDeltaTime 33 -> 0.033 s
    0xCC,                    // 71 imageShiftConfidence 204 -> 0.8
    0x01, 0x00,              // 72 outputShifts[0] 256 x pi/32767 rad
    0xFF, 0x00,              // 74 outputShifts[1] -256 x pi/32767 rad
    0x02,                    // 76 rangeSource RANGE_SRC_LASER
    0x13,                    // 77 leapSeconds 19
    0x05,                    // 78 panAlignment 5 -> 0.005 rad
    0xFB,                    // 79 tiltAlignment -5 -> -0.005 rad
    0x01,                    // 80 insRotationOption insInPlatform
    0x7F, 0xFF,              // 81 insQuat[0] 1.0             (only if insRotationOption != 0)
    0x00, 0x01,              // 83 insQuat[1] 1/32767
    0xFF, 0xFF,              // 85 insQuat[2] -1/32767
    0x10, 0x00,              // 87 insQuat[3] 4096/32767
};

const Bytes performance_golden{
    0x00, 0x7B, 0x01, 0xC8,  //  0 RmsQuad 123, 456 -> 0.000123, 0.000456
    0x03, 0xE8, 0x07, 0xD0,  //  4 RmsDir 1000, 2000 -> 0.001, 0.002
    0x05, 0xDC, 0x08, 0xCA,  //  8 RmsVel 1500, 2250 -> 1.5, 2.25
    0x01, 0xF4, 0x02, 0xEE,  // 12 RmsPos 500, 750 -> 0.0005, 0.00075
    0x0C, 0x80, 0x03, 0x20,  // 16 Iout 3200, 800 -> 3.2 A, 0.8 A
};

const Bytes diagnostics_golden{
    0x5E, 0x3B,  //  0 Voltage24 24123 -> 24.123 V
    0x2F, 0x12,  //  2 Voltage12 12050 -> 12.05 V
    0x0C, 0xE5,  //  4 Voltage3v3 3301 -> 3.301 V
    0x04, 0xE2,  //  6 Current24 1250 -> 1.25 A
    0x01, 0xF4,  //  8 Current12 500 -> 0.5 A
    0x00, 0x7D,  // 10 Current3v3 125 -> 0.125 A
    0x2D,        // 12 CrownTemp 45 C
    0xF6,        // 13 SlaTemp -10 C
    0x26,        // 14 GyroTemp 38 C
    0x00,        // 15 reserved
    0x00, 0x7B,  // 16 Voltage24Var 123 -> 0.00123
    0x00, 0x2D,  // 18 Voltage12Var 45 -> 0.00045
    0x00, 0x01,  // 20 Voltage3v3Var 1 -> 0.00001
    0x00, 0x14,  // 22 Current24Var 20 -> 0.0002
    0x00, 0x1E,  // 24 Current12Var 30 -> 0.0003
    0xFF, 0xFF,  // 26 Current3v3Var 65535 -> 0.65535
};

const Bytes software_golden{
    0x02,        //  0 sourceBoard BOARD_CROWN
    0x02,        //  1 numCores 2
    0x00, 0x00,  //  2 reserved
    // core 0
    0x80,                                //  4 cpuLoad 128 -> 128/2.55 %
    0x40,                                //  5 heapLoad 64 -> 64/2.55 %
    0x20,                                //  6 stackLoad 32 -> 32/2.55 %
    0x00,                                //  7 reserved
    0x02,                                //  8 numThreads 2
    0x66, 0x33, 0x19, 0xCC, 0x64, 0x0F,  //  9 thread 0: cpu 40 %, heap 20 %, stack 25/2.55 %,
                                         //    watchdog 80 %, 100 -> 1000 iterations, worst 1.5
    0x01, 0x02, 0x03, 0xFF, 0x0A, 0xFF,  // 15 thread 1: 1, 2, 3 /2.55 %, watchdog 100 %,
                                         //    10 -> 100 iterations, worst 25.5
    // core 1
    0x33,                                // 21 cpuLoad 51 -> 20 %
    0x11,                                // 22 heapLoad 17 -> 17/2.55 %
    0x22,                                // 23 stackLoad 34 -> 34/2.55 %
    0x00,                                // 24 reserved
    0x01,                                // 25 numThreads 1
    0x05, 0x06, 0x07, 0x08, 0x09, 0x0A,  // 26 thread 0
};

// FftData element i: Frequency (i+1) x 256 raw, Accel 0x10+i, 0x20+i, 0x30+i, Gyro 0x40+i, ...
const Bytes vibration_golden{
    0x40, 0x00, 0xE0, 0x00, 0x7F, 0xFF,  //  0 MaxAccel 16384, -8192, 32767 (x 20/32767 m/s/s)
    0x10, 0x00, 0xF0, 0x00, 0x08, 0x00,  //  6 MaxGyro 4096, -4096, 2048 (x 0.1/32767 rad/s)
    0x01, 0x00, 0x10, 0x20, 0x30, 0x40, 0x50, 0x60,  //  12 FftData[0]
    0x02, 0x00, 0x11, 0x21, 0x31, 0x41, 0x51, 0x61,  //  20 FftData[1]
    0x03, 0x00, 0x12, 0x22, 0x32, 0x42, 0x52, 0x62,  //  28 FftData[2]
    0x04, 0x00, 0x13, 0x23, 0x33, 0x43, 0x53, 0x63,  //  36 FftData[3]
    0x05, 0x00, 0x14, 0x24, 0x34, 0x44, 0x54, 0x64,  //  44 FftData[4]
    0x06, 0x00, 0x15, 0x25, 0x35, 0x45, 0x55, 0x65,  //  52 FftData[5]
    0x07, 0x00, 0x16, 0x26, 0x36, 0x46, 0x56, 0x66,  //  60 FftData[6]
    0x08, 0x00, 0x17, 0x27, 0x37, 0x47, 0x57, 0x67,  //  68 FftData[7]
    0x09, 0x00, 0x18, 0x28, 0x38, 0x48, 0x58, 0x68,  //  76 FftData[8]
    0x0A, 0x00, 0x19, 0x29, 0x39, 0x49, 0x59, 0x69,  //  84 FftData[9]
    0x0B, 0x00, 0x1A, 0x2A, 0x3A, 0x4A, 0x5A, 0x6A,  //  92 FftData[10]
    0x0C, 0x00, 0x1B, 0x2B, 0x3B, 0x4B, 0x5B, 0x6B,  // 100 FftData[11]
    0x0D, 0x00, 0x1C, 0x2C, 0x3C, 0x4C, 0x5C, 0x6C,  // 108 FftData[12]
    0x0E, 0x00, 0x1D, 0x2D, 0x3D, 0x4D, 0x5D, 0x6D,  // 116 FftData[13]
    0x0F, 0x00, 0x1E, 0x2E, 0x3E, 0x4E, 0x5E, 0x6E,  // 124 FftData[14]
    0x10, 0x00, 0x1F, 0x2F, 0x3F, 0x4F, 0x5F, 0x6F,  // 132 FftData[15]
};

const Bytes network_golden{
    0x10, 0x43,              //  0 Flags 0x1043
    0x01, 0x02, 0x03, 0x04,  //  2 RxBytes
    0x05, 0x06, 0x07, 0x08,  //  6 TxBytes
    0x00, 0x00, 0xAB, 0xCD,  // 10 RxPackets
    0x00, 0x00, 0x12, 0x34,  // 14 TxPackets
    0x00, 0x01,              // 18 RxErrors
    0x00, 0x02,              // 20 TxErrors
    0x00, 0x03,              // 22 RxDrops
    0x00, 0x04,              // 24 TxDrops
    0x00, 0x05,              // 26 RxFifoErrors
    0x00, 0x06,              // 28 TxFifoErrors
    0x00, 0x07,              // 30 FrameErrors
    0x00, 0x08,              // 32 Collisions
    0x00, 0x09,              // 34 CarrierErrors
};

const Bytes retract_golden{
    0x01,        // 0 Cmd RETRACT_CMD_DEPLOY
    0x03,        // 1 State RETRACT_STATE_DEPLOYING
    0x06, 0x19,  // 2 Pos 1561 -> 1.561 rad
    0x00, 0xA5,  // 4 Flags 0x00A5
};

const Bytes stare_golden{
    0x00, 0xBC, 0x61, 0x4E,  //  0 systemTime 12345678 ms
    0x64,                    //  4 maxStareTime 100 -> 1.0 s
    0xF8,                    //  5 bits 7..3: along, prevByTime, startedByTime, dataValid, reset
    0x4B,                    //  6 prevStareTime 75 -> 0.75 s
    0x99,                    //  7 stareLoad 153 -> 0.6
    0x1B, 0x3D, 0x44, 0x40,  //  8 posLat 45.7 deg
    0xB7, 0x94, 0x92, 0x40,  // 12 posLon -121.5 deg
    0x00, 0x26, 0x25, 0xA0,  // 16 posAlt 2500000 -> 250 m
    0x1B, 0x3B, 0xBD, 0xA0,  // 20 gimbalPosLat 45.69 deg       (optional from here)
    0xB7, 0x96, 0x18, 0xE0,  // 24 gimbalPosLon -121.49 deg
    0x00, 0xE4, 0xE1, 0xC0,  // 28 gimbalPosAlt 15000000 -> 1500 m
    0x40, 0x00, 0xC0, 0x00,  // 32 gimbalQuat[0..1] 16384, -16384
    0x20, 0x00, 0xE0, 0x00,  // 36 gimbalQuat[2..3] 8192, -8192
    0x20, 0x00,              // 40 pan 8192 x pi/32767 rad
    0xD0, 0x00,              // 42 tilt -12288 x pi/32767 rad
    0x05,                    // 44 rangeSource RANGE_SRC_INTERNAL_DTED
    0x01, 0xE2, 0x40,        // 45 slantRange 123456 -> 1234.56 m
    0x04, 0x00,              // 48 alongStareAngle 1024 x pi/32767 rad
    0xFC, 0x00,              // 50 crossStareAngle -1024 x pi/32767 rad
};

const Bytes reset_golden{
    0x00, 0x00, 0x00, 0x10,  // 0 Vector 0x10
    0x08, 0x00, 0xAB, 0xCD,  // 4 Address 0x0800ABCD
    0x03,                    // 8 sourceBoard BOARD_PAYLOAD (optional)
};

const Bytes debug_golden{
    0x02,  // 0 source BOARD_CROWN
    0x02,  // 1 priority debugLevelWarn
    0x00,  // 2 reserved1
    0x00,  // 3 reserved2
    'G',  'y', 'r', 'o', ' ', 't', 'e', 'm', 'p', ' ', 'h', 'i', 'g', 'h',  // 4 description
    0x00,                                                                   // 18 terminator
};

const Bytes klv_golden{
    0x02,                          // 0 Key 2
    0x01,                          // 1 SubKey 1
    0x05,                          // 2 Length 5
    0xDE, 0xAD, 0xBE, 0xEF, 0x42,  // 3 Value
};

const Bytes gps_golden{
    0x83,                    //  0 multiAntHeadingValid 1, reserved 000, FixType threeDFix (3)
    0x0D,                    //  1 FixState 0x0D
    0x0C,                    //  2 TrackedSats 12
    0x11,                    //  3 PDOP 17 -> 1.7
    0x1B, 0x3D, 0x44, 0x40,  //  4 Latitude 45.7 deg
    0xB7, 0x94, 0x92, 0x40,  //  8 Longitude -121.5 deg
    0x00, 0x26, 0x25, 0xA0,  // 12 Altitude 250 m
    0x00, 0x00, 0x04, 0xD2,  // 16 VelNED[0] 1234 -> 1.234 m/s
    0xFF, 0xFF, 0xF6, 0x3C,  // 20 VelNED[1] -2500 -> -2.5 m/s
    0x00, 0x00, 0x00, 0x7D,  // 24 VelNED[2] 125 -> 0.125 m/s
    0x00, 0x00, 0x09, 0xC4,  // 28 Hacc 2500 -> 2.5 m
    0x00, 0x00, 0x0F, 0xA0,  // 32 Vacc 4000 -> 4 m
    0x00, 0x00, 0x01, 0x2C,  // 36 SpeedAcc 300 -> 0.3 m/s
    0x00, 0x00, 0xC3, 0x50,  // 40 HeadingAcc 50000 -> 50000/5729578 rad (about 0.5 deg)
    0x1D, 0xCD, 0x65, 0x00,  // 44 ITOW 500000000 ms
    0x08, 0x98,              // 48 Week 2200
    0xF4, 0x2F,              // 50 GeoidUndulation -3025 -> -30.25 m
    0x04,                    // 52 source novatelSource
    0x03,                    // 53 reserved 000000, detailedAccuracyValid 1, verticalVelocityValid 1
    0x12,                    // 54 leapSeconds 18                 (optional from here)
    0x20, 0x00,              // 55 multiAntHeading 8192 x pi/32767 rad (if multiAntHeadingValid)
    0x05, 0xDC, 0x07, 0xD0, 0x0C, 0xB2,  // 57 posAccuracy 1.5, 2.0, 3.25 m (if detailed...)
    0x00, 0x64, 0x00, 0xC8, 0x01, 0x5E,  // 63 velAccuracy 0.1, 0.2, 0.35 m/s (if detailed...)
};

const Bytes ins_golden{
    0x00, 0x01, 0xE2, 0x40,  //  0 systemTime 123456 ms
    0x06,                    //  4 gpsSource piksiSource
    0x04,                    //  5 reserved 00000, imuType imuTypeEpson (4)
    0x05,                    //  6 insMode insModeRunTight
    0xFF,                    //  7 has gyro, gravity, accel, clock, panTilt; pos, vel, hdg rejected
    0x19,                    //  8 gpsPeriod 25 -> 0.25 s
    0x64,                    //  9 hdgPeriod 100 -> 1.0 s
    0x3F, 0x00,              // 10 posChiSquare F16:9 1.5 (exp 31, sig 0x100)
    0x40, 0x00,              // 12 velChiSquare F16:9 2.0
    0x41, 0x40,              // 14 hdgChiSquare F16:9 3.25
    0x00, 0x7B, 0x00, 0x2D, 0x03, 0xE8,  // 16 attConfidence 0.0123, 0.0045, 0.1 rad
    0x00, 0x0C, 0x00, 0x22, 0x00, 0x38,  // 22 velConfidence 0.12, 0.34, 0.56 m/s
    0x00, 0x96, 0x00, 0xFA, 0x01, 0x77,  // 28 posConfidence 1.5, 2.5, 3.75 m
    0x00, 0x0A, 0x00, 0x14, 0x00, 0x1E,  // 34 gyroConfidence 0.0001..0.0003 rad/s (hasGyroBias)
    0x01, 0x2C, 0x02, 0x58, 0x03, 0x84,  // 40 accelConfidence 0.01, 0.02, 0.03 (hasAccelBias)
    0x05, 0xDC,                          // 46 gravityConfidence 0.05 (hasGravityBias)
    0x13, 0x88,                          // 48 clockBiasConfidence 0.5 m (hasClockBias)
    0x09, 0xC4,                          // 50 clockDriftConfidence 0.25 m/s (hasClockBias)
    0x00, 0x0C, 0xFF, 0xDE, 0x00, 0x38,  // 52 gyroBias 0.00012, -0.00034, 0.00056 (hasGyroBias)
    0x0B, 0xB8, 0x17, 0x70, 0x00, 0x96,  // 58 accelBias 0.1, 0.2, 0.005 (hasAccelBias)
    0x01, 0x2C,                          // 64 gravityBias 0.01 (hasGravityBias)
    0xFB, 0x1E,                          // 66 clockBias -1250 -> -12.5 m (hasClockBias)
    0x04, 0xD2,                          // 68 clockDrift 1234 -> 1.234 m/s (hasClockBias)
    0x07,                                // 70 numTightSatPosUpdates 7
    0x08,                                // 71 numTightSatVelUpdates 8
    0x0E,                                // 72 numTightPosUpdates 14
    0x10,                                // 73 numTightVelUpdates 16
    0x08, 0x00, 0xF8, 0x00,  // 74 panTiltBias 2048, -2048 x (10 pi/180)/32767 (hasPanTiltBias)
    0x33,                    // 78 panTiltChiSquare 51 -> 2.0 (hasPanTiltBias)
};

inline const std::vector<GoldenVector> telemetry_vectors{
    {pkt::geolocate_telemetry, "geolocate_telemetry", &geolocate_golden},
    {pkt::performance, "performance", &performance_golden},
    {pkt::diagnostics, "diagnostics", &diagnostics_golden},
    {pkt::software_diagnostics, "software_diagnostics", &software_golden},
    {pkt::vibration, "vibration", &vibration_golden},
    {pkt::network_diagnostics, "network_diagnostics", &network_golden},
    {pkt::retract_status, "retract_status", &retract_golden},
    {pkt::stare_start, "stare_start", &stare_golden},
    {pkt::reset_source, "reset_source", &reset_golden},
    {pkt::debug_string, "debug_string", &debug_golden},
    {pkt::klv_user_data, "klv_user_data", &klv_golden},
    {pkt::gps_data, "gps_data", &gps_golden},
    {pkt::ins_quality, "ins_quality", &ins_golden},
};

}  // namespace gimbal::orion::golden_vectors
