// Golden frames: two published HEARTBEATs (a MAVLink 1 example frame and a MAVLink 2 capture
// from a Pixhawk running ArduPilot) and, for every message, v1 and v2 frames computed by hand
// from the common.xml definitions (field order by size, little-endian, CRC over length..payload
// plus CRC_EXTRA) with a separate implementation of the checksum. The encoder must produce the
// bytes and the framer must decode them to the same values.
#include <catch2/catch.hpp>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "helpers.hpp"

using namespace mavtest;

namespace {

// Decodes one complete frame; fails the test unless exactly one message comes out of it.
Message decode_one(const Bytes& frame, FramerOptions options = {}) {
    Framer framer(options);
    const std::vector<Message> got = framer.push(frame);
    REQUIRE(got.size() == 1);
    CHECK(framer.stats().frame_bytes == frame.size());
    CHECK(framer.pending_bytes() == 0);
    return got[0];
}

struct Golden {
    std::string what;
    Payload payload;
    Bytes v1;  // seq 7, sysid 1, compid 1
    Bytes v2;
};

std::vector<Golden> goldens() {
    RcChannels rc;
    rc.time_boot_ms = 5000;
    rc.chancount = 8;
    rc.chan_raw = {1500,   1500,   1000,   1500,   1800,   1200,   1500,   1500,   0xFFFF,
                   0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF};
    rc.rssi = 200;
    return {
        {"HEARTBEAT of a GCS (type 6 GCS, autopilot 8 invalid)",
         Heartbeat{0, 6, 8, 0, 0, 3},
         {0xFE, 0x09, 0x07, 0x01, 0x01, 0x00,        // len 9, seq 7, sys 1, comp 1, id 0
          0x00, 0x00, 0x00, 0x00,                    // custom_mode 0
          0x06, 0x08, 0x00, 0x00, 0x03,              // type, autopilot, base, status, ver
          0x76, 0x50},                               // CRC 0x5076
         {0xFD, 0x09, 0x00, 0x00, 0x07, 0x01, 0x01,  // len 9, flags 0 0, seq, sys, comp
          0x00, 0x00, 0x00,                          // id 0 (24 bits)
          0x00, 0x00, 0x00, 0x00, 0x06, 0x08, 0x00, 0x00, 0x03,  // (last byte 3: no truncation)
          0x28, 0x51}},                                          // CRC 0x5128
        {"SYSTEM_TIME 2023-11-14T22:13:20.123456Z",
         SystemTime{1700000000123456ull, 123456},
         {0xFE, 0x0C, 0x07, 0x01, 0x01, 0x02,              // len 12, id 2
          0x40, 0x22, 0x20, 0x18, 0x24, 0x0A, 0x06, 0x00,  // time_unix_usec 0x00060A2418202240
          0x40, 0xE2, 0x01, 0x00,                          // time_boot_ms 123456
          0x23, 0x30},
         {0xFD, 0x0B, 0x00, 0x00, 0x07, 0x01, 0x01, 0x02, 0x00, 0x00,  // len 11: one zero cut
          0x40, 0x22, 0x20, 0x18, 0x24, 0x0A, 0x06, 0x00, 0x40, 0xE2,
          0x01,  // time_boot_ms, top zero byte cut
          0xEA, 0x4C}},
        {"ATTITUDE with yawspeed 0",
         Attitude{1000, 0.25f, -0.5f, 1.5f, 0.125f, -0.0625f, 0.0f},
         {0xFE, 0x1C, 0x07, 0x01, 0x01, 0x1E,  // len 28, id 30
          0xE8, 0x03, 0x00, 0x00,              // time_boot_ms 1000
          0x00, 0x00, 0x80, 0x3E,              // roll 0.25f
          0x00, 0x00, 0x00, 0xBF,              // pitch -0.5f
          0x00, 0x00, 0xC0, 0x3F,              // yaw 1.5f
          0x00, 0x00, 0x00, 0x3E,              // rollspeed 0.125f
          0x00, 0x00, 0x80, 0xBD,              // pitchspeed -0.0625f
          0x00, 0x00, 0x00, 0x00,              // yawspeed 0
          0x97, 0xE7},
         {0xFD, 0x18, 0x00, 0x00, 0x07, 0x01, 0x01, 0x1E, 0x00, 0x00,  // len 24: yawspeed cut
          0xE8, 0x03, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3E, 0x00, 0x00, 0x00, 0xBF, 0x00,
          0x00, 0xC0, 0x3F, 0x00, 0x00, 0x00, 0x3E, 0x00, 0x00, 0x80, 0xBD, 0xEB, 0xF6}},
        {"GLOBAL_POSITION_INT at 47.3977420 N 8.5455940 E",
         GlobalPositionInt{123456, 473977420, 85455940, 488000, 10000, 100, -50, 0, 9000},
         {0xFE, 0x1C, 0x07, 0x01, 0x01, 0x21,  // len 28, id 33
          0x40, 0xE2, 0x01, 0x00,              // time_boot_ms 123456
          0x4C, 0x52, 0x40, 0x1C,              // lat 473977420 degE7
          0x44, 0xF4, 0x17, 0x05,              // lon 85455940 degE7
          0x40, 0x72, 0x07, 0x00,              // alt 488000 mm
          0x10, 0x27, 0x00, 0x00,              // relative_alt 10000 mm
          0x64, 0x00, 0xCE, 0xFF, 0x00, 0x00,  // vx 100, vy -50, vz 0 cm/s
          0x28, 0x23,                          // hdg 9000 cdeg
          0xBA, 0x20},
         {0xFD, 0x1C, 0x00, 0x00, 0x07, 0x01, 0x01, 0x21, 0x00, 0x00,  // len 28 (hdg != 0)
          0x40, 0xE2, 0x01, 0x00, 0x4C, 0x52, 0x40, 0x1C, 0x44, 0xF4,
          0x17, 0x05, 0x40, 0x72, 0x07, 0x00, 0x10, 0x27, 0x00, 0x00,
          0x64, 0x00, 0xCE, 0xFF, 0x00, 0x00, 0x28, 0x23, 0x2E, 0xA6}},
        {"RC_CHANNELS, 8 channels",
         rc,
         {0xFE, 0x2A, 0x07, 0x01, 0x01, 0x41,              // len 42, id 65
          0x88, 0x13, 0x00, 0x00,                          // time_boot_ms 5000
          0xDC, 0x05, 0xDC, 0x05, 0xE8, 0x03, 0xDC, 0x05,  // chan1..4: 1500 1500 1000 1500
          0x08, 0x07, 0xB0, 0x04, 0xDC, 0x05, 0xDC, 0x05,  // chan5..8: 1800 1200 1500 1500
          0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,  // chan9..18 unused
          0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
          0x08, 0xC8,  // chancount 8, rssi 200 (after chans)
          0x9A, 0x8C},
         {0xFD, 0x2A, 0x00, 0x00, 0x07, 0x01, 0x01, 0x41, 0x00, 0x00, 0x88, 0x13, 0x00, 0x00,
          0xDC, 0x05, 0xDC, 0x05, 0xE8, 0x03, 0xDC, 0x05, 0x08, 0x07, 0xB0, 0x04, 0xDC, 0x05,
          0xDC, 0x05, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
          0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x08, 0xC8, 0xA1, 0x35}},
    };
}

}  // namespace

TEST_CASE("published MAVLink 1 HEARTBEAT example frame", "[mavlink][golden]") {
    // Quadrotor (type 2), ArduPilot (autopilot 3), base_mode 0x51, MAV_STATE_ACTIVE (4),
    // seq 0x4E, system 1, component 1.
    const Bytes frame{0xFE, 0x09, 0x4E, 0x01, 0x01, 0x00, 0x00, 0x00, 0x00,
                      0x00, 0x02, 0x03, 0x51, 0x04, 0x03, 0x1C, 0x7F};
    const Message m = decode_one(frame);
    CHECK(m.version == 1);
    CHECK(m.seq == 0x4E);
    CHECK(m.sysid == 1);
    CHECK(m.compid == 1);
    CHECK(m.msgid == 0);
    const Heartbeat want{0, 2, 3, 0x51, 4, 3};
    REQUIRE(std::holds_alternative<Heartbeat>(m.payload));
    CHECK(std::get<Heartbeat>(m.payload) == want);
    CHECK_FALSE(armed(want));
    CHECK(system_state(want) == MavState::active);
    CHECK(is_autopilot(want));
    CHECK(encode_v1(want, 1, 1, 0x4E) == frame);
}

TEST_CASE("MAVLink 2 HEARTBEAT captured from a Pixhawk", "[mavlink][golden]") {
    // seq 0xEF, MAV_STATE_STANDBY (3); otherwise as the v1 example.
    const Bytes frame{0xFD, 0x09, 0x00, 0x00, 0xEF, 0x01, 0x01, 0x00, 0x00, 0x00, 0x00,
                      0x00, 0x00, 0x00, 0x02, 0x03, 0x51, 0x03, 0x03, 0x73, 0x89};
    const Message m = decode_one(frame);
    CHECK(m.version == 2);
    CHECK(m.seq == 0xEF);
    const Heartbeat want{0, 2, 3, 0x51, 3, 3};
    CHECK(m.payload == Payload{want});
    CHECK(encode_v2(want, 1, 1, 0xEF) == frame);
}

TEST_CASE("every message encodes to its golden v1 and v2 frames and decodes back",
          "[mavlink][golden]") {
    for (const Golden& g : goldens()) {
        CAPTURE(g.what);
        CHECK(encode_v1(g.payload, 1, 1, 7) == g.v1);
        CHECK(encode_v2(g.payload, 1, 1, 7) == g.v2);
        const Message m1 = decode_one(g.v1);
        CHECK(m1 == Message{1, 7, 1, 1, message_id(g.payload), g.payload, {}});
        const Message m2 = decode_one(g.v2);
        CHECK(m2 == Message{2, 7, 1, 1, message_id(g.payload), g.payload, {}});
    }
}

TEST_CASE("armed() reads MAV_MODE_FLAG_SAFETY_ARMED", "[mavlink][heartbeat]") {
    Heartbeat hb{0, 2, 3, 0x51, 4, 3};
    CHECK_FALSE(armed(hb));
    hb.base_mode = 0x51 | 0x80;  // ArduPilot's armed base_mode 0xD1
    CHECK(armed(hb));
    hb.base_mode = 0x80;
    CHECK(armed(hb));
    hb.base_mode = 0x7F;
    CHECK_FALSE(armed(hb));
    const Heartbeat gcs{0, 6, 8, 0xC0, 0, 3};
    CHECK_FALSE(is_autopilot(gcs));
}

TEST_CASE("MAVLink 2 leaves out trailing zero bytes and keeps at least one",
          "[mavlink][truncation]") {
    SECTION("an all-zero payload is one byte long") {
        const Heartbeat zero{0, 0, 0, 0, 0, 0};
        const Bytes frame = encode_v2(zero, 1, 1, 0);
        CHECK(frame[1] == 1);
        CHECK(frame.size() == header_size_v2 + 1 + checksum_size);
        CHECK(decode_one(frame).payload == Payload{zero});
    }
    SECTION("random messages with zero tails") {
        std::mt19937 rng(3);
        for (std::size_t i = 0; i < 500; ++i) {
            const Payload p = random_payload(rng, i, i % 2 == 0);
            const Bytes full = payload_of(p);
            std::size_t want = full.size();
            while (want > 1 && full[want - 1] == 0) --want;
            const Bytes frame = encode_v2(p, 9, 8, static_cast<std::uint8_t>(i));
            CHECK(frame[1] == want);
            CHECK(frame.size() == header_size_v2 + want + checksum_size);
            const Message m = decode_one(frame);
            CHECK(m.payload == p);
            CHECK(m.sysid == 9);
            CHECK(m.compid == 8);
            CHECK(m.seq == static_cast<std::uint8_t>(i));
        }
    }
    SECTION("a v2 frame cut shorter than the encoder would still reads as zeros") {
        // A sender may truncate differently (here: every byte after time_boot_ms).
        const Attitude att{0x01020304, 0, 0, 0, 0, 0, 0};
        const Bytes frame =
            raw_v2(Attitude::id, Bytes{0x04, 0x03, 0x02, 0x01}, Attitude::crc_extra);
        CHECK(decode_one(frame).payload == Payload{att});
    }
}

TEST_CASE("v1 frames are never truncated", "[mavlink][truncation]") {
    const Heartbeat zero{0, 0, 0, 0, 0, 0};
    const Bytes frame = encode_v1(zero, 1, 1, 0);
    CHECK(frame[1] == Heartbeat::length);
    CHECK(decode_one(frame).payload == Payload{zero});
}

TEST_CASE("bytes past the known fields are extension fields and are ignored",
          "[mavlink][truncation]") {
    std::mt19937 rng(4);
    for (std::size_t which = 0; which < 5; ++which) {
        const Payload p = random_payload(rng, which);
        Bytes longer = payload_of(p);
        longer.insert(longer.end(), {0x11, 0x22, 0x33});
        const MessageInfo* info = find_message(message_id(p));
        REQUIRE(info != nullptr);
        CHECK(decode_one(raw_v2(info->id, longer, info->crc_extra)).payload == p);
        CHECK(decode_one(raw_v1(static_cast<std::uint8_t>(info->id), longer, info->crc_extra))
                  .payload == p);
    }
}

TEST_CASE("payloads are the known lengths and round-trip", "[mavlink][codec]") {
    std::mt19937 rng(5);
    for (std::size_t i = 0; i < 500; ++i) {
        const Payload p = random_payload(rng, i);
        const Bytes bytes = payload_of(p);
        const MessageInfo* info = find_message(message_id(p));
        REQUIRE(info != nullptr);
        CHECK(bytes.size() == info->length);
        const auto back = decode_payload(info->id, bytes);
        REQUIRE(back);
        CHECK(*back == p);
        CHECK(decode_one(encode_v1(p, 1, 1, 0)).payload == p);
    }
    CHECK_FALSE(decode_payload(1, Bytes(31, 0)));  // SYS_STATUS: not ours
}
