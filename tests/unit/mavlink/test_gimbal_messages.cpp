// Gimbal-manager messages and MAVLink 2 signing against golden frames. The golden bytes were
// packed by a one-off script straight from the common.xml definitions (field order by type
// size, extensions last, trailing zeros cut, CRC_EXTRA from the definition text) and hashed
// with Python's hashlib, not with this codec.
#include <catch2/catch.hpp>
#include <cmath>

#include "helpers.hpp"

using namespace mavtest;

namespace {

const Bytes golden_command_long{0xFD, 0x20, 0x00, 0x00, 0x03, 0xFF, 0xBE, 0x4C, 0x00, 0x00, 0x00,
                                0x00, 0xF0, 0xC1, 0x00, 0x00, 0x34, 0x42, 0x00, 0x00, 0xC0, 0x7F,
                                0x00, 0x00, 0xC0, 0x7F, 0x00, 0x00, 0x80, 0x41, 0x00, 0x00, 0x00,
                                0x00, 0x00, 0x00, 0x80, 0x3F, 0xE8, 0x03, 0x01, 0x9A, 0xF9, 0x95};
const Bytes golden_command_int{
    0xFD, 0x21, 0x00, 0x00, 0x04, 0xFF, 0xBE, 0x4B, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3F, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x4C, 0x52, 0x40, 0x1C,
    0x44, 0xF4, 0x17, 0x05, 0x00, 0x00, 0xCC, 0x41, 0xC3, 0x00, 0x01, 0x9A, 0x06, 0x78, 0x31};
const Bytes golden_command_ack{0xFD, 0x0A, 0x00, 0x00, 0x05, 0x01, 0x9A, 0x4D, 0x00, 0x00, 0xE8,
                               0x03, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0xFF, 0xBE, 0x10, 0x36};
const Bytes golden_attitude_status{
    0xFD, 0x31, 0x00, 0x00, 0x06, 0x01, 0x9A, 0x1D, 0x01, 0x00, 0xD2, 0x04, 0x00, 0x00, 0x00, 0x00,
    0x80, 0x3F, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0xC0, 0x7F, 0x00, 0x00, 0xC0, 0x7F, 0x00, 0x00, 0xC0, 0x7F, 0x00, 0x00, 0x00, 0x00, 0x50, 0x00,
    0x00, 0x00, 0x00, 0x00, 0xC0, 0x7F, 0x00, 0x00, 0xC0, 0x7F, 0x01, 0x85, 0x25};
const Bytes golden_set_pitchyaw{0xFD, 0x16, 0x00, 0x00, 0x08, 0xFF, 0xBE, 0x1F, 0x01,
                                0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xBF,
                                0x00, 0x00, 0x80, 0x3E, 0x00, 0x00, 0xC0, 0x7F, 0x00,
                                0x00, 0xC0, 0x7F, 0x01, 0x9A, 0xAC, 0x79};
const Bytes golden_manager_status{0xFD, 0x0B, 0x00, 0x00, 0x09, 0x01, 0x9A, 0x19,
                                  0x01, 0x00, 0x88, 0x13, 0x00, 0x00, 0x18, 0x00,
                                  0x00, 0x00, 0x01, 0xFF, 0xBE, 0x1B, 0x74};
// HEARTBEAT from 255/190, key 00 01 .. 1F, link 2, timestamp 0x123456789A.
const Bytes golden_signed_heartbeat{0xFD, 0x09, 0x01, 0x00, 0x01, 0xFF, 0xBE, 0x00, 0x00,
                                    0x00, 0x00, 0x00, 0x00, 0x00, 0x06, 0x08, 0x00, 0x00,
                                    0x03, 0xAB, 0x5D, 0x02, 0x9A, 0x78, 0x56, 0x34, 0x12,
                                    0x00, 0xB0, 0xC4, 0x62, 0x38, 0x69, 0x0E};

SigningKey test_key() {
    SigningKey key{};
    for (std::size_t i = 0; i < key.size(); ++i) key[i] = static_cast<std::uint8_t>(i);
    return key;
}

Message decode_single(const Bytes& frame, FramerOptions options = {}) {
    Framer framer(std::move(options));
    std::vector<Message> got = framer.push(frame);
    REQUIRE(got.size() == 1);
    return got[0];
}

}  // namespace

TEST_CASE("gimbal-manager messages encode to the golden frames") {
    CommandLong cl;
    cl.param = {-30, 45, nan_f, nan_f, 16, 0, 1};
    cl.command = mav_cmd::do_gimbal_manager_pitchyaw;
    cl.target_system = 1;
    cl.target_component = 154;
    CHECK(encode_v2(cl, 255, 190, 3) == golden_command_long);

    CommandInt ci;
    ci.param1 = 1;
    ci.x = 473977420;
    ci.y = 85455940;
    ci.z = 25.5f;
    ci.command = mav_cmd::do_set_roi_location;
    ci.target_system = 1;
    ci.target_component = 154;
    ci.frame = mav_frame::global_relative_alt_int;
    CHECK(encode_v2(ci, 255, 190, 4) == golden_command_int);

    CommandAck ack{1000, 2, 0, 0, 255, 190};
    CHECK(encode_v2(ack, 1, 154, 5) == golden_command_ack);

    GimbalDeviceAttitudeStatus st;
    st.time_boot_ms = 1234;
    st.q = {1, 0, 0, 0};
    st.flags = gimbal_flags::yaw_in_earth_frame | gimbal_flags::yaw_lock;
    st.gimbal_device_id = 1;
    CHECK(encode_v2(st, 1, 154, 6) == golden_attitude_status);

    GimbalManagerSetPitchyaw py;
    py.pitch = -0.5f;
    py.yaw = 0.25f;
    py.target_system = 1;
    py.target_component = 154;
    CHECK(encode_v2(py, 255, 190, 8) == golden_set_pitchyaw);

    GimbalManagerStatus ms{5000, 24, 1, 255, 190, 0, 0};
    CHECK(encode_v2(ms, 1, 154, 9) == golden_manager_status);
}

TEST_CASE("gimbal-manager messages decode from the golden frames") {
    const Message m = decode_single(golden_command_long);
    CHECK(m.sysid == 255);
    CHECK(m.compid == 190);
    const auto& cl = std::get<CommandLong>(m.payload);
    CHECK(cl.param[0] == -30.0f);
    CHECK(cl.param[1] == 45.0f);
    CHECK(std::isnan(cl.param[2]));
    CHECK(std::isnan(cl.param[3]));
    CHECK(cl.param[4] == 16.0f);
    CHECK(cl.param[6] == 1.0f);
    CHECK(cl.command == 1000);
    CHECK(cl.target_component == 154);

    const auto ci = std::get<CommandInt>(decode_single(golden_command_int).payload);
    CHECK(ci.x == 473977420);
    CHECK(ci.y == 85455940);
    CHECK(ci.z == 25.5f);
    CHECK(ci.frame == 6);
    CHECK(ci.command == 195);

    const auto ack = std::get<CommandAck>(decode_single(golden_command_ack).payload);
    CHECK(ack == CommandAck{1000, 2, 0, 0, 255, 190});

    const auto st =
        std::get<GimbalDeviceAttitudeStatus>(decode_single(golden_attitude_status).payload);
    CHECK(st.gimbal_device_id == 1);
    CHECK(st.q[0] == 1.0f);
    CHECK(std::isnan(st.delta_yaw));

    const auto py = std::get<GimbalManagerSetPitchyaw>(decode_single(golden_set_pitchyaw).payload);
    CHECK(py.pitch == -0.5f);
    CHECK(py.yaw == 0.25f);
    CHECK(std::isnan(py.pitch_rate));
}

TEST_CASE("extension fields: absent ones read as zero, v1 leaves them out") {
    // A COMMAND_ACK from a MAVLink 1 sender: 3 bytes, extensions zero.
    CommandAck ack{531, 3, 0, 0, 0, 0};
    const Bytes v1 = encode_v1(ack, 1, 154, 0);
    CHECK(v1.size() == header_size_v1 + 3 + checksum_size);
    CHECK(std::get<CommandAck>(decode_single(v1).payload) == ack);
    // Extensions with values travel in v2 and survive.
    CommandAck full{531, 0, 50, -7, 255, 190};
    CHECK(std::get<CommandAck>(decode_single(encode_v2(full, 1, 154, 0)).payload) == full);
    // Every message round-trips through v2 with all-zero fields cut to one byte.
    for (const Payload& p : {Payload{CameraInformation{}}, Payload{GimbalManagerInformation{}},
                             Payload{GimbalDeviceInformation{}}, Payload{GimbalManagerStatus{}},
                             Payload{GimbalDeviceSetAttitude{}}, Payload{CameraFovStatus{}}}) {
        const Bytes f = encode_v2(p, 1, 154, 0);
        const Message m = decode_single(f);
        CHECK(m.msgid == message_id(p));
        CHECK(encode_v2(m.payload, 1, 154, 0) == f);
    }
}

TEST_CASE("CAMERA_INFORMATION and GIMBAL_DEVICE_INFORMATION carry strings and extensions") {
    GimbalDeviceInformation gi;
    const std::string vendor = "Trillium";
    std::copy(vendor.begin(), vendor.end(), gi.vendor_name.begin());
    gi.gimbal_device_id = 2;
    gi.cap_flags2 = 0x12345678;
    gi.pitch_min = -2.0f;
    const Bytes f = encode_v2(gi, 1, 154, 0);
    CHECK(f.size() == header_size_v2 + GimbalDeviceInformation::max_length + checksum_size);
    const auto back = std::get<GimbalDeviceInformation>(decode_single(f).payload);
    CHECK(back.vendor_name == gi.vendor_name);
    CHECK(back.gimbal_device_id == 2);
    CHECK(back.cap_flags2 == 0x12345678);
    CHECK(back.pitch_min == -2.0f);

    CameraInformation ci;
    ci.camera_device_id = 1;
    ci.gimbal_device_id = 1;
    ci.flags = camera_cap_has_basic_zoom;
    const Bytes c = encode_v2(ci, 1, 154, 0);
    CHECK(c.size() == header_size_v2 + CameraInformation::max_length + checksum_size);
    CHECK(std::get<CameraInformation>(decode_single(c).payload) == ci);
}

TEST_CASE("MAVLink 2 signing: golden frame, verify, tamper, replay") {
    const SigningKey key = test_key();
    Heartbeat hb{0, 6, 8, 0, 0, 3};
    Bytes f = encode_v2(hb, 255, 190, 1, true);
    append_signature(f, key, 2, 0x123456789A);
    CHECK(f == golden_signed_heartbeat);
    CHECK(verify_signature(key, f));

    SECTION("any changed byte fails") {
        for (std::size_t i = 0; i < f.size(); ++i) {
            Bytes bad = f;
            bad[i] ^= 0x01;
            CHECK_FALSE(verify_signature(key, bad));
        }
        SigningKey other = key;
        other[31] ^= 0x80;
        CHECK_FALSE(verify_signature(other, f));
    }
    SECTION("the framer verifies with the key") {
        const Message m = decode_single(f, {.accept_signed = true, .signing_key = key});
        REQUIRE(m.signature);
        CHECK(m.signature->verified);
        CHECK(m.signature->link_id == 2);
        CHECK(m.signature->timestamp == 0x123456789A);
        SigningKey other = key;
        other[0] = 0xFF;
        const Message w = decode_single(f, {.accept_signed = true, .signing_key = other});
        REQUIRE(w.signature);
        CHECK_FALSE(w.signature->verified);
    }
    SECTION("replay: per (sysid, compid, link) stream, strictly increasing") {
        SigningStreams streams;
        const std::uint64_t local = 1'000'000'000;
        CHECK(streams.accept(255, 190, 0, local - 10, local));
        CHECK_FALSE(streams.accept(255, 190, 0, local - 10, local));  // the same frame again
        CHECK_FALSE(streams.accept(255, 190, 0, local - 11, local));
        CHECK(streams.accept(255, 190, 0, local - 9, local));
        CHECK(streams.accept(255, 190, 1, local - 100, local));  // another link: own stream
        CHECK(streams.accept(254, 190, 0, local - 100, local));
        // A new stream more than one minute old is refused.
        CHECK_FALSE(streams.accept(250, 1, 0, local - 6'000'001, local));
        CHECK(streams.accept(250, 1, 0, local - 6'000'000, local));
    }
    SECTION("streams saved and restored: a frame from before a restart is still a replay") {
        SigningStreams before;
        const std::uint64_t local = 2'000'000'000;
        REQUIRE(before.accept(255, 190, 0, local - 50, local));
        REQUIRE(before.accept(254, 1, 3, local - 70, local));
        const auto saved = before.streams();
        CHECK(saved.size() == 2);
        CHECK(before.latest() == local - 50);
        SigningStreams after;  // the restarted daemon
        after.restore(saved);
        CHECK(after.streams() == saved);
        CHECK_FALSE(after.accept(255, 190, 0, local - 50, local + 10));  // the captured frame
        CHECK_FALSE(after.accept(254, 1, 3, local - 80, local + 10));
        CHECK(after.accept(255, 190, 0, local - 49, local + 10));
        // Restoring never lowers what is known.
        after.restore({{255, 190, 0, 5}});
        CHECK_FALSE(after.accept(255, 190, 0, local - 49, local + 10));
        SigningClock clock;
        clock.raise_to(local);
        CHECK(clock.next(local - 1000) == local + 1);  // the system clock went back
    }
    SECTION("timestamps") {
        CHECK(signing_timestamp(signing_epoch_unix_s) == 0);
        CHECK(signing_timestamp(signing_epoch_unix_s + 1.5) == 150000);
        CHECK(signing_timestamp(0) == 0);
        SigningClock clock;
        CHECK(clock.next(100) == 100);
        CHECK(clock.next(100) == 101);
        CHECK(clock.next(50) == 102);
        CHECK(clock.next(200) == 200);
    }
}
