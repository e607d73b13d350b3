// Byte vectors for the Viewpro tests: hex strings as the ICD prints them, and the hand-written
// golden frames (from the ICD's tables, every field non-zero). Not a test file itself.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace viewpro_test {

using Bytes = std::vector<std::uint8_t>;

// "FE FB 00 ..." (spaces optional, either case) -> bytes.
inline Bytes hex(std::string_view text) {
    auto nibble = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    Bytes out;
    int high = -1;
    for (const char c : text) {
        if (c == ' ' || c == '\n') continue;
        const int v = nibble(c);
        if (v < 0) throw std::invalid_argument("bad hex digit");
        if (high < 0) {
            high = v;
        } else {
            out.push_back(static_cast<std::uint8_t>(high * 16 + v));
            high = -1;
        }
    }
    if (high >= 0) throw std::invalid_argument("odd number of hex digits");
    return out;
}

inline Bytes concat(const std::vector<Bytes>& parts) {
    Bytes out;
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}

// ICD 4.2.1 feedback example: pitch 27, yaw 16, distance 0, lon 79.8812446, lat 6.9428789.
inline const Bytes icd_out1 =
    hex("FE FB 00 00 D8 41 00 00 80 41 00 00 00 00 1E E9 9C 2F 35 66 23 04 67");

// ICD 4.1.2 IN2 example without its 10 extra zero bytes (errata): 2021-08-07 17:27:58,
// attitude 0, lat 23.1234567, lon 113.1234567, alt 11 m, velocity 0. The checksum AC is
// unchanged: zeros add nothing.
inline const Bytes icd_in2_example_50 =
    hex("F9 FC E5 07 08 07 11 1B 3A 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 07 5C C8 "
        "0D 07 45 6D 43 F8 2A 00 00 00 00 00 00 00 00 00 00 00 00 AC");
inline const Bytes icd_in2_example_40 =
    hex("F9 FC E5 07 08 07 11 1B 3A 00 00 00 00 00 00 00 00 00 00 00 00 07 5C C8 0D 07 45 6D 43 "
        "F8 2A 00 00 00 00 00 00 00 00 AC");

// IN1: 2024-03-15 12:34:56, roll 5, pitch -3, yaw 120 deg (float rad), lat 47.3977419,
// lon 8.5455938 (degE7), alt 488.123 m (mm).
inline const Bytes golden_in1 =
    hex("F9 FB E8 07 03 0F 0C 22 38 C2 B8 B2 3D 50 77 56 BD 92 0A 06 40 4B 52 40 1C 42 F4 17 05 "
        "BB 72 07 00 FF");
// IN2: IN1's fields plus velocity [12.34, -5.67, 0.89] m/s (cm/s int16: 1234, -567, 89).
inline const Bytes golden_in2 =
    hex("F9 FC E8 07 03 0F 0C 22 38 C2 B8 B2 3D 50 77 56 BD 92 0A 06 40 4B 52 40 1C 42 F4 17 05 "
        "BB 72 07 00 D2 04 C9 FD 59 00 F5");
// IN3: year byte 23 (2023), flag FF, 11-02 07:08:09, LRF 1234.567 m (mm), pitch -12.345,
// yaw 270.5 (degE3), lat -33.8688197, lon 151.2092955, alt 58.25 m, velocity
// [-1.5, 2.25, -0.75] m/s.
inline const Bytes golden_in3 =
    hex("F9 FC 17 FF 0B 02 07 08 09 87 D6 12 00 C7 CF FF FF A4 20 04 00 3B 07 D0 EB 1B B5 20 5A "
        "8A E3 00 00 6A FF E1 00 B5 FF AD");

// OUT2: 2022-06-30 23:59:58, zoom 1234, gimbal roll 1.5, pitch -30, yaw 45 deg (float rad),
// LRF 523.25 m, UAV roll -2, pitch 4, yaw -160 deg (float rad), UAV alt 1234.567 m (mm), UAV
// lat 6.9428789, lon 79.8812446, target lat 6.95, lon 79.89 (double rad).
inline const Bytes golden_out2 =
    hex("FE FC E6 07 06 1E 17 3B 3A D2 04 50 77 D6 3C 92 0A 06 BF DB 0F 49 3F 00 D0 02 44 35 FA "
        "0E BD 35 FA 8E 3D C2 B8 32 C0 87 D6 12 00 10 C9 F9 8A 65 05 BF 3F 9D 81 0D F0 9A 4E F6 "
        "3F 60 24 09 BA 8A 0D BF 3F B3 0B D3 2B 3B 4F F6 3F 51");
// OUT3: OUT2's fields, with UAV and target lat/lon as degE7.
inline const Bytes golden_out3 =
    hex("FE FD E6 07 06 1E 17 3B 3A D2 04 50 77 D6 3C 92 0A 06 BF DB 0F 49 3F 00 D0 02 44 35 FA "
        "0E BD 35 FA 8E 3D C2 B8 32 C0 87 D6 12 00 35 66 23 04 1E E9 9C 2F 60 7C 24 04 20 3F 9E "
        "2F C3");
// OUT4: year byte 25 (2025), flag FF, 01-02 03:04:05, zoom 4321, gimbal roll 0.5, pitch
// -45.123, yaw 90.001 (degE3), LRF 987.654 m (mm), target alt 12.345 m, UAV pitch 2.5, yaw
// -170.25 (degE3), UAV alt 321.5 m, UAV lat -22.9068467, lon -43.1728965, target lat -22.91,
// lon -43.17 (degE7).
inline const Bytes golden_out4 =
    hex("FE FD 19 FF 01 02 03 04 05 E1 10 F4 01 00 00 BD 4F FF FF 91 5F 01 00 06 12 0F 00 39 30 "
        "00 00 C4 09 00 00 F6 66 FD FF DC E7 04 00 4D B1 58 F2 BB 56 44 E6 20 36 58 F2 E0 C7 44 "
        "E6 73");

}  // namespace viewpro_test
