// Golden SIYI frames and where each comes from. Not a test file itself.
//
// [SDK] "SIYI Gimbal Camera External SDK Protocol", v0.1.1 (2025-02-26), chapter 4
//       "Communication Data Example" (the publicly distributed PDF; a text extraction is in
//       github.com/rutger-seascape/siyi_sdk, SIYI_SDK_PROTOCOL.txt). The frames are quoted
//       byte for byte; where the extraction broke a line, the byte count follows Data_len.
// [SDK-old] The same chapter of earlier SDK editions (A8 mini user manual v1.x, section 3.3),
//       as public clients quote it ("ground truth messages from documentation").
// [MK15] SIYI MK15 user manual v1.4, section 4.8 "SIYI Datalink SDK": the one reply SIYI
//       documents, in the same frame format (CTRL 02, the device's own SEQ).
// [capture] Replies recorded from cameras, quoted in the comments of public open-source
//       clients found by code search; CRC-valid, their repositories not named by the index.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace siyi_test {

using Bytes = std::vector<std::uint8_t>;

inline Bytes hex(std::string_view text) {
    Bytes out;
    int nibble = -1;
    for (const char c : text) {
        int v = -1;
        if (c >= '0' && c <= '9') v = c - '0';
        if (c >= 'a' && c <= 'f') v = c - 'a' + 10;
        if (c >= 'A' && c <= 'F') v = c - 'A' + 10;
        if (v < 0) continue;
        if (nibble < 0) {
            nibble = v;
        } else {
            out.push_back(static_cast<std::uint8_t>(nibble << 4 | v));
            nibble = -1;
        }
    }
    return out;
}

inline Bytes concat(const std::vector<Bytes>& parts) {
    Bytes out;
    for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}

struct Golden {
    std::string_view what;  // the example's title in its source
    std::string_view source;
    Bytes bytes;
};

// Requests, as a controller sends them (CTRL 01 need_ack).
inline const std::vector<Golden>& sdk_requests() {
    static const std::vector<Golden> v = {
        {"TCP heartbeat", "SDK ch.2 0x00 and ch.3", hex("55 66 01 01 00 00 00 00 00 59 8B")},
        {"zoom 1", "SDK", hex("55 66 01 01 00 00 00 05 01 8d 64")},
        {"zoom -1", "SDK", hex("55 66 01 01 00 00 00 05 FF 5c 6a")},
        {"Absolute Zoom (4.5x)", "SDK", hex("55 66 01 02 00 01 00 0F 04 05 60 BB")},
        {"focus 1", "SDK", hex("55 66 01 01 00 00 00 06 01 de 31")},
        {"Take Photo", "SDK", hex("55 66 01 01 00 00 00 0c 00 34 ce")},
        {"Start Video Recording", "SDK", hex("55 66 01 01 00 00 00 0c 02 76 ee")},
        {"Pan/Tilt 100 100", "SDK", hex("55 66 01 02 00 00 00 07 64 64 3d cf")},
        {"Auto Focus", "SDK", hex("55 66 01 05 00 00 00 04 01 2c 01 64 00 1f 8a")},
        {"focus -1", "SDK", hex("55 66 01 01 00 00 00 06 ff 0f 3f")},
        {"One-Key Centering", "SDK", hex("55 66 01 01 00 00 00 08 01 d1 12")},
        {"Gimbal Status Information", "SDK", hex("55 66 01 00 00 00 00 0a 0f 75")},
        {"Retrieve Hardware ID", "SDK", hex("55 66 01 00 00 00 00 02 07 f4")},
        {"Retrieve Firmware Version", "SDK", hex("55 66 01 00 00 00 00 01 64 c4")},
        {"Lock Mode", "SDK", hex("55 66 01 01 00 00 00 0c 03 57 fe")},
        {"Follow Mode", "SDK", hex("55 66 01 01 00 00 00 0c 04 b0 8e")},
        {"FPV Mode", "SDK", hex("55 66 01 01 00 00 00 0c 05 91 9e")},
        {"Retrieve Attitude Data", "SDK", hex("55 66 01 00 00 00 00 0d e8 05")},
        {"Set Gimbal Control Angle (-90, 0) (Facing Down)", "SDK",
         hex("55 66 01 04 00 00 00 0E 00 00 7C FC 4F A4")},
        {"Set HDMI Video Output", "SDK", hex("55 66 01 01 00 00 00 0c 06 f2 ae")},
        {"Set CVBS Video Output", "SDK", hex("55 66 01 01 00 00 00 0c 07 d3 be")},
        {"Disable CVBS and HDMI Output", "SDK", hex("55 66 01 01 00 00 00 0c 08 3c 4f")},
        {"Read Laser Ranging Distance", "SDK", hex("55 66 01 00 00 00 00 15 D1 96")},
        {"Retrieve Maximum Zoom Value in Current State", "SDK",
         hex("55 66 01 00 00 00 00 16 B2 A6")},
        {"Retrieve Current Zoom Value", "SDK", hex("55 66 01 00 00 00 00 18 7C 47")},
        {"Retrieve Current Gimbal Mode", "SDK", hex("55 66 01 00 00 00 00 19 5D 57")},
        // Printed with its bytes over two lines; Data_len 0x20 = 32 bytes: time 0, lat
        // 22.27683, lon 114.17612 (the SDK's caption swaps the two names), then zeros.
        {"Send GPS Coordinates", "SDK",
         hex("55 66 01 20 00 01 00 3e 00 00 00 00 ac 2c 47 0d b0 e4 0d 44 00 00 00 00 00 00 00"
             " 00 00 00 00 00 00 00 00 00 00 00 00 00 80 62")},
        {"Auto Focus (one byte)", "SDK-old", hex("55 66 01 01 00 00 00 04 01 bc 57")},
        {"Gimbal Speed (32, 32)", "SDK-old", hex("55 66 01 02 00 00 00 07 20 20 75 06")},
    };
    return v;
}

// SDK examples of commands gimbald does not declare: they frame, and decode as unknown.
inline const std::vector<Golden>& sdk_undeclared() {
    static const std::vector<Golden> v = {
        {"Retrieve Current Video Stitching Mode", "SDK", hex("55 66 01 00 00 00 00 10 74 c6")},
        {"Set Current Video Stitching Mode", "SDK", hex("55 66 01 01 00 00 00 11 01 3a ab")},
        {"Retrieve Temperature at a Specific Point", "SDK",
         hex("55 66 01 05 00 00 00 12 00 00 00 00 01 a8 2f")},
        {"Retrieve Max/Min Temperatures of Entire Image", "SDK",
         hex("55 66 01 01 00 00 00 14 01 cf 54")},
        {"Retrieve Pseudo-Color Settings", "SDK", hex("55 66 01 00 00 00 00 1A 3e 67")},
        {"Set Pseudo-Color Mode (Iron Red)", "SDK", hex("55 66 01 01 00 00 00 1B 03 b3 64")},
        {"Retrieve Camera Encoding Parameters", "SDK", hex("55 66 01 01 00 00 00 20 00 BF 8D")},
        {"Set Camera Encoding Parameters: Main Stream HD H.265 1.5M", "SDK",
         hex("55 66 01 09 00 00 00 21 01 02 00 05 d0 02 dc 05 00 58 45")},
        {"Set Recording Stream 4K H.265 15M", "SDK",
         hex("55 66 01 09 00 00 00 21 00 02 00 0f 70 08 98 3a 00 70 be")},
        {"Request Thermal Imaging Output Mode", "SDK", hex("55 66 01 00 00 00 00 33 75 d2")},
        {"Set Thermal Imaging Output Mode", "SDK", hex("55 66 01 01 00 00 00 34 01 29 52")},
        {"Retrieve Single Frame of Raw Thermal Imaging Data", "SDK",
         hex("55 66 01 00 00 00 00 35 b3 b2")},
        {"Request Remote Controller Hardware ID", "MK15", hex("55 66 01 00 00 00 00 40 81 9c")},
    };
    return v;
}

// Replies from devices (CTRL 02 ack_pack, the device's own SEQ).
inline const Bytes mk15_hardware_id_reply =  // [MK15] "6801130111", cmd 0x40
    hex("55 66 02 0C 00 09 00 40 36 38 30 31 31 33 30 31 31 31 00 00 7b 8b");
inline const Bytes captured_attitude_reply =  // [capture] yaw -0.9, pitch -88.0, rates
    hex("55 66 02 0c 00 06 00 0d f7 ff 90 fc 00 00 fd ff 7f ff 00 00 89 4b");
inline const Bytes captured_attitude_reply2 =  // [capture] yaw 2.6, pitch -179.9
    hex("55 66 02 0c 00 44 00 0d 1a 00 f9 f8 00 00 fc ff ff ff fd ff 19 88");

}  // namespace siyi_test
