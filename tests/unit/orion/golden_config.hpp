// Golden byte vectors of the config packets, written by hand from the ICD tables (one comment
// per field). Shared by the unit tests (tests/unit/orion/test_packets_config.cpp) and the
// dissector test (tests/dissector/), which decodes every vector with the codec and with
// dissectors/gimbald.lua and compares.
#pragma once

#include "golden_vector.hpp"

namespace gimbal::orion::golden_vectors {

const Bytes uart_config_golden{
    0x04,              // 0: port = USER_DATA_PORT_FP1 (4)
    0x01, 0xC2, 0x00,  // 1..3: baud = 115200
    0x03,              // 4: protocol = PROTOCOL_ORION (3)
    0x01,              // 5: temporary = 1 (optional)
};

const Bytes limits_golden{
    0xF4, 0x48, 0xFA, 0x24,  // 0..3: MinPos = [-3.0, -1.5] rad x 1000
    0x0B, 0xB8, 0x05, 0xDC,  // 4..7: MaxPos = [3.0, 1.5] rad x 1000
    0x09, 0xC4, 0x04, 0xE2,  // 8..11: MaxVel = [2.5, 1.25] rad/s x 1000
    0x00, 0x14, 0x00, 0x0A,  // 12..15: MaxAccel = [20, 10] rad/s^2 x 1
    0x04, 0xB0, 0x03, 0x20,  // 16..19: ContCur = [1.2, 0.8] A x 1000
    0x0D, 0xAC, 0x0A, 0xBE,  // 20..23: PeakCur = [3.5, 2.75] A x 1000
    0x01, 0xF4, 0x00, 0xFA,  // 24..27: PeakCurTime = [0.5, 0.25] s x 1000
    0x02, 0x58, 0x01, 0x90,  // 28..31: InitCur = [0.6, 0.4] A x 1000
    0x28, 0x1E,              // 32..33: MaxPower = [40, 30] W (optional)
};

const Bytes ins_options_golden{
    0xFF,  // 0:7..0:0: platformRotation, courseIsHeading, disableMag, disableGPS, resetINS,
           //          disableGpsClockError, accelBias, tightlyCoupled = all 1
    0xF9,  // 1:7..1:4: usePhaseForVelocity, disableL1, disableL2, disableL5 = 1;
           // 1:3..1:0: elevationMask = 9 (3 degrees)
    0xF5,  // 2:7..2:4: payloadIns, nonLinearHeading, sensonorMV, HD25PayloadINS = 1;
           // 2:3..2:0: opticalFlowSetting = 5
    0x00,  // 3: reserved B8
    0x20, 0x00, 0xF0, 0x00, 0x40, 0x00,  // 4..9: gimbalToPlatformEuler = [8192, -4096, 16384]
                                         //       x pi/32767 rad
    0x10, 0x00,                          // 10..11: initialHeading = 4096 x pi/32767 rad
    0x01, 0xF4, 0xFF, 0x06, 0x03, 0xE8,  // 12..17: gpsLeverArm = [0.5, -0.25, 1.0] m x 1000
    0xFC, 0x00,                          // 18..19: headingObservationBiasAngle = -1024 steps
    0x05, 0xDC, 0xFC, 0x18, 0x00, 0x7D,  // 20..25: secondGPSLeverArm = [1.5, -1.0, 0.125] m
    0x08, 0x00,                          // 26..27: alignHeadingNoise = 2048 x pi/65535 rad
};

const Bytes network_settings_golden{
    0xC0, 0xA8, 0x01, 0x14,  // 0..3: Ip = 192.168.1.20
    0xFF, 0xFF, 0xFF, 0x00,  // 4..7: Mask = 255.255.255.0
    0xC0, 0xA8, 0x01, 0x01,  // 8..11: Gateway = 192.168.1.1
    0x01,                    // 12: LowDelay = 1 (optional)
    0x05, 0x78,              // 13..14: Mtu = 1400 (optional)
};

const Bytes network_video_golden{
    0xEF, 0x01, 0x02, 0x03,  // 0..3: DestIp = 239.1.2.3
    0x3A, 0x9C,              // 4..5: Port = 15004
    0x00, 0x3D, 0x09, 0x00,  // 6..9: Bitrate = 4000000 (optional)
    0x05,                    // 10: Ttl = 5 (optional)
    0x01,                    // 11: StreamType = STREAM_TYPE_MJPEG (optional)
    0x50,                    // 12: MjpegQuality = 80 (optional)
    0xB8,                    // 13:7 SaveSettings = 1; 13:6..13:3 TsPacketCount = 7 (optional)
};

const Bytes cameras_golden{
    0x02,              // 0: NumCameras = 2
    0x00, 0x00, 0x00,  // 1..3: reserved
    // camera 0
    0x01,                    // 4: Type = CAMERA_TYPE_VISIBLE
    0x06,                    // 5: Proto = CAMERA_PROTO_SONY
    0x00, 0x00, 0x10, 0xCC,  // 6..9: MinFocalLength = 4.3 mm x 1000
    0x00, 0x01, 0xF7, 0xE8,  // 10..13: MaxFocalLength = 129.0 mm x 1000
    0x06, 0x0E,              // 14..15: PixelPitch = 0.00155 mm x 1e6
    0x07, 0x80,              // 16..17: ArrayWidth = 1920
    0x04, 0x38,              // 18..19: ArrayHeight = 1080
    0xFF, 0x00, 0xFF, 0x80,  // 20..23: AlignMin = [-256, -128] x pi/32767 rad
    0x01, 0x00, 0x00, 0x80,  // 24..27: AlignMax = [256, 128] x pi/32767 rad
    // camera 1
    0x04,                    // 28: Type = CAMERA_TYPE_LWIR
    0x01,                    // 29: Proto = CAMERA_PROTO_FLIR
    0x00, 0x00, 0x61, 0xA8,  // 30..33: MinFocalLength = 25.0 mm x 1000
    0x00, 0x00, 0xC3, 0x50,  // 34..37: MaxFocalLength = 50.0 mm x 1000
    0x42, 0x68,              // 38..39: PixelPitch = 0.017 mm x 1e6
    0x02, 0x80,              // 40..41: ArrayWidth = 640
    0x02, 0x00,              // 42..43: ArrayHeight = 512
    0xFF, 0xC0, 0xFF, 0xE0,  // 44..47: AlignMin = [-64, -32] x pi/32767 rad
    0x00, 0x40, 0x00, 0x20,  // 48..51: AlignMax = [64, 32] x pi/32767 rad
};

const Bytes clevis_version_golden = join({
    text("1.2.3", 16),         // 0..15: Version
    text("CLV-100-A", 16),     // 16..31: PartNumber
    {0x00, 0x01, 0xE2, 0x40},  // 32..35: OnTime = 123456 min (optional)
});

const Bytes crown_version_golden = join({
    text("4.0.1", 16),         // 0..15: Version
    text("CRN-300-C", 16),     // 16..31: PartNumber
    {0x00, 0x00, 0x27, 0x10},  // 32..35: OnTime = 10000 min (optional)
});

const Bytes payload_version_golden = join({
    text("2.5.0-rc1+build.77", 24),  // 0..23: Version (24 bytes for this board)
    text("PLD-200-B", 16),           // 24..39: PartNumber
    {0x00, 0x00, 0x00, 0x07},        // 40..43: OnTime = 7 min (optional)
});

const Bytes tracker_version_golden = join({
    text("7.1", 16),    // 0..15: Version
    text("TRK-9", 16),  // 16..31: PartNumber
});

const Bytes retract_version_golden{
    0x52, 0x31, 0x2E, 0x30, 0x00, 0x00, 0x00, 0x00,  // 0..15: Version = "R1.0", zero padded
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
};

const Bytes lensctl_version_golden = text("LC-0.9.12", 16);  // 0..15: Version

const Bytes board_golden{
    0x00, 0x0F, 0x42, 0x41,  // 0..3: boardSN = 1000001
    0x00, 0x1E, 0x84, 0x82,  // 4..7: assemblySN = 2000002
    0xDE, 0xAD, 0xBE, 0xEF,  // 8..11: config = 0xDEADBEEF
    0x00, 0x00, 0x00,        // 12..14: reserved
    0x02,                    // 15: boardEnum = crown (2)
    0x30, 0xEF,  // 16..17: manufactureDate year 24 (0011000) month 7 (0111) day 15 (01111)
    0x32, 0x7C,  // 18..19: calibrationDate year 25 (0011001) month 3 (0011) day 28 (11100)
};

const Bytes autopilot_data_golden{
    0x01,        // 0: IsFlying = 1
    0x01,        // 1: CommGood = 1
    0x00, 0xFA,  // 2..3: Agl = 250 m
};

const Bytes ext_heading_data_golden{
    0x20, 0x00,  // 0..1: extHeading = 8192 x pi/32767 rad
    0x01, 0x00,  // 2..3: noise = 256 x 2pi/65535 rad
    0xC0, 0x00,  // 4:7 headingInGimbalAxis = 1, 4:6 headingFromAlign = 1, 14 reserved bits
    0xF8, 0x00,  // 6..7: pitch = -2048 x pi/32767 rad (optional)
};

const Bytes range_data_golden{
    0x00, 0x01, 0xE2, 0x40,  // 0..3: range = 1234.56 m x 100
    0x01, 0xF4,              // 4..5: maxAgeMs = 500
    0x02,                    // 6: source = RANGE_SRC_LASER
};

inline const std::vector<GoldenVector> config_vectors{
    {pkt::uart_config, "uart_config", &uart_config_golden},
    {pkt::limits, "limits", &limits_golden},
    {pkt::ins_options, "ins_options", &ins_options_golden},
    {pkt::network_settings, "network_settings", &network_settings_golden},
    {pkt::network_video, "network_video", &network_video_golden},
    {pkt::cameras, "cameras", &cameras_golden},
    {pkt::clevis_version, "clevis_version", &clevis_version_golden},
    {pkt::crown_version, "crown_version", &crown_version_golden},
    {pkt::payload_version, "payload_version", &payload_version_golden},
    {pkt::tracker_version, "tracker_version", &tracker_version_golden},
    {pkt::retract_version, "retract_version", &retract_version_golden},
    {pkt::lensctl_version, "lensctl_version", &lensctl_version_golden},
    {pkt::board, "board", &board_golden},
    {pkt::autopilot_data, "autopilot_data", &autopilot_data_golden},
    {pkt::ext_heading_data, "ext_heading_data", &ext_heading_data_golden},
    {pkt::range_data, "range_data", &range_data_golden},
};

}  // namespace gimbal::orion::golden_vectors
