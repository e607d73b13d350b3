// The message declarations against the SDK's tables: lengths, scalings, rounding,
// saturation, short and long payloads, JSON.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "protocols/siyi/codec/json.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "vectors.hpp"

using namespace gimbal::siyi;
using namespace siyi_test;

namespace {

template <class M>
Bytes payload(const M& m) {
    const Payload p = encode_payload(m);
    return Bytes(p.view().begin(), p.view().end());
}

template <class M>
Decoded<M> decode_bytes(const Bytes& b) {
    return decode<M>(std::span<const std::uint8_t>(b));
}

}  // namespace

TEST_CASE("message lengths follow the SDK's tables", "[siyi][messages]") {
    // Requests.
    CHECK(max_length<TcpHeartbeat>() == 1);
    CHECK(max_length<FirmwareVersionRequest>() == 0);
    CHECK(min_length<AutoFocus>() == 1);
    CHECK(max_length<AutoFocus>() == 5);
    CHECK(max_length<ManualZoom>() == 1);
    CHECK(max_length<GimbalRotation>() == 2);
    CHECK(max_length<Center>() == 1);
    CHECK(max_length<Capture>() == 1);
    CHECK(max_length<SetGimbalAttitude>() == 4);
    CHECK(max_length<AbsoluteZoom>() == 2);
    CHECK(max_length<AircraftAttitude>() == 28);
    CHECK(max_length<DataStreamRequest>() == 2);
    CHECK(max_length<SetUtcTime>() == 8);
    CHECK(max_length<RawGps>() == 32);
    // Replies.
    CHECK(min_length<FirmwareVersion>() == 8);
    CHECK(max_length<FirmwareVersion>() == 12);
    CHECK(max_length<HardwareId>() == 12);
    CHECK(max_length<ManualZoomReply>() == 2);
    CHECK(max_length<CenterReply>() == 1);
    CHECK(min_length<CameraSystemInfo>() == 5);
    CHECK(max_length<CameraSystemInfo>() == 8);
    CHECK(max_length<FunctionFeedback>() == 1);
    CHECK(max_length<GimbalAttitude>() == 12);
    CHECK(max_length<SetGimbalAttitudeReply>() == 6);
    CHECK(max_length<LaserDistance>() == 2);
    CHECK(max_length<ZoomRange>() == 2);
    CHECK(max_length<LaserTarget>() == 8);
    CHECK(max_length<CurrentZoom>() == 2);
    CHECK(max_length<GimbalMode>() == 1);
    CHECK(max_length<DataStreamReply>() == 1);
    CHECK(max_length<MagneticEncoder>() == 6);
}

TEST_CASE("angles are int16 tenths of a degree, little-endian, rounded half away from zero",
          "[siyi][messages][encode]") {
    CHECK(payload(SetGimbalAttitude{60.5, -45.0}) == hex("5D 02 3E FE"));  // 605, -450
    CHECK(payload(SetGimbalAttitude{0.05, -0.05}) == hex("01 00 FF FF"));  // half away
    CHECK(payload(SetGimbalAttitude{0.0499, -0.0499}) == hex("00 00 00 00"));
    CHECK(payload(SetGimbalAttitude{12.25, -12.25}) == hex("7B 00 85 FF"));  // 122.5 -> 123
    // Saturation inside the codec; NaN encodes as 0.
    CHECK(payload(SetGimbalAttitude{1e9, -1e9}) == hex("FF 7F 00 80"));
    CHECK(payload(SetGimbalAttitude{std::nan(""), std::numeric_limits<double>::infinity()}) ==
          hex("00 00 FF 7F"));
}

TEST_CASE("zoom is an integer byte and a tenths byte", "[siyi][messages][encode]") {
    CHECK(payload(AbsoluteZoom{4.5}) == hex("04 05"));
    CHECK(payload(AbsoluteZoom{30.0}) == hex("1E 00"));
    CHECK(payload(AbsoluteZoom{4.25}) == hex("04 03"));  // 42.5 tenths -> 43
    CHECK(payload(AbsoluteZoom{1.04}) == hex("01 00"));
    CHECK(payload(AbsoluteZoom{1e6}) == hex("FF 09"));  // saturates at 255.9
    CHECK(payload(AbsoluteZoom{-3}) == hex("00 00"));
    CHECK(decode_bytes<CurrentZoom>(hex("0A 03")).value.zoom == Approx(10.3));
    CHECK(decode_bytes<ZoomRange>(hex("1E 00")).value.zoom_max == 30.0);
    // The 0x05 reply counts tenths in one uint16 instead.
    CHECK(payload(ManualZoomReply{12.3}) == hex("7B 00"));
    CHECK(decode_bytes<ManualZoomReply>(hex("2C 01")).value.zoom == Approx(30.0));
}

TEST_CASE("positions are degE7, altitudes cm, speeds mm/s", "[siyi][messages][encode]") {
    RawGps g;
    g.time_boot_ms = 0x01020304;
    g.lat = -33.8688197;
    g.lon = 151.2092955;
    g.alt_msl = 12.125;        // 1212.5 cm -> 1213
    g.alt_ellipsoid = -0.125;  // -12.5 cm -> -13
    g.vn = 0.0625;             // 62.5 mm/s -> 63
    g.ve = -2.5;
    g.vd = 0;
    const Bytes p = payload(g);
    REQUIRE(p.size() == 32);
    CHECK(Bytes(p.begin(), p.begin() + 4) == hex("04 03 02 01"));
    const auto back = decode_bytes<RawGps>(p);
    REQUIRE(back.ok());
    CHECK(back.value.lat == Approx(-33.8688197).margin(1e-7));
    CHECK(back.value.lon == Approx(151.2092955).margin(1e-7));
    CHECK(back.value.alt_msl == Approx(12.13));
    CHECK(back.value.alt_ellipsoid == Approx(-0.13));
    CHECK(back.value.vn == Approx(0.063));
    CHECK(back.value.ve == Approx(-2.5));

    const auto t = decode_bytes<LaserTarget>(hex("B0 E4 0D 44 AC 2C 47 0D"));  // lon, then lat
    REQUIRE(t.ok());
    CHECK(t.value.lon == Approx(114.17612));
    CHECK(t.value.lat == Approx(22.27683));
}

TEST_CASE("the aircraft's attitude travels as IEEE floats in radians", "[siyi][messages]") {
    AircraftAttitude a;
    a.time_boot_ms = 1000;
    a.roll = 0.1f;
    a.yaw = -3.0f;
    a.yaw_rate = 0.25f;
    const Bytes p = payload(a);
    REQUIRE(p.size() == 28);
    CHECK(Bytes(p.begin() + 4, p.begin() + 8) == hex("CD CC CC 3D"));  // 0.1f
    const auto back = decode_bytes<AircraftAttitude>(p);
    REQUIRE(back.ok());
    CHECK(back.value.roll == 0.1f);
    CHECK(back.value.yaw == -3.0f);
    const auto j = to_json(back.value);
    CHECK(j["yaw"].get<double>() == Approx(-3.0 * 180 / 3.14159265358979323846));
    CHECK(j["yaw_rate"].get<double>() == Approx(0.25 * 180 / 3.14159265358979323846));
}

TEST_CASE("decoders reject short payloads and read the known part of long ones",
          "[siyi][messages][decode]") {
    CHECK(decode_bytes<GimbalAttitude>(hex("01 00 02 00 03 00 04 00 05 00 06")).error ==
          DecodeError::too_short);
    CHECK(decode_bytes<SetGimbalAttitude>(hex("01")).error == DecodeError::too_short);
    CHECK(decode_bytes<HardwareId>(hex("37 41 31 32")).error == DecodeError::too_short);
    CHECK(decode_bytes<Center>({}).error == DecodeError::too_short);

    const auto longer = decode_bytes<GimbalAttitude>(
        hex("01 00 02 00 03 00 04 00 05 00 06 00 AA BB CC"));  // newer firmware's extra bytes
    REQUIRE(longer.ok());
    CHECK(longer.value.yaw == Approx(0.1));
    CHECK(longer.value.roll_rate == Approx(0.6));
}

TEST_CASE("optional trailing fields keep their defaults when absent", "[siyi][messages][decode]") {
    // The A8 mini answers 0x01 with camera and gimbal only.
    const auto a8 = decode_bytes<FirmwareVersion>(hex("08 02 00 00 09 03 00 00"));
    REQUIRE(a8.ok());
    CHECK(version_string(a8.value.camera) == "0.2.8");
    CHECK(version_string(a8.value.gimbal) == "0.3.9");
    CHECK(a8.value.zoom == 0);
    // A cut-off optional field is absent, not an error.
    const auto cut = decode_bytes<FirmwareVersion>(hex("08 02 00 00 09 03 00 00 06 01"));
    REQUIRE(cut.ok());
    CHECK(cut.value.zoom == 0);
    // Older 0x0A replies stop after the motion mode.
    const auto info = decode_bytes<CameraSystemInfo>(hex("00 01 00 01 02"));
    REQUIRE(info.ok());
    CHECK(info.value.hdr);
    CHECK(info.value.record == RecordStatus::recording);
    CHECK(info.value.motion_mode == MotionMode::fpv);
    CHECK(info.value.mounting == MountingDirection::normal);  // default
    const auto full = decode_bytes<CameraSystemInfo>(hex("00 00 00 02 00 02 01 01"));
    REQUIRE(full.ok());
    CHECK(full.value.record == RecordStatus::no_card);
    CHECK(full.value.mounting == MountingDirection::inverted);
    CHECK(full.value.video_output == VideoOutput::cvbs);
    CHECK(full.value.zoom_linkage);
}

TEST_CASE("firmware version words ignore their high byte", "[siyi][messages]") {
    CHECK(version_string(0x6E030203) == "3.2.3");  // the SDK's example
    const auto fw = decode_bytes<FirmwareVersion>(hex("03 02 03 6E 08 02 00 00 06 01 00 00"));
    REQUIRE(fw.ok());
    const auto j = to_json(fw.value);
    CHECK(j["camera"] == "3.2.3");
    CHECK(j["gimbal"] == "0.2.8");
    CHECK(j["zoom"] == "0.1.6");
    // The word is kept whole, so the frame re-encodes as it came.
    CHECK(payload(fw.value) == hex("03 02 03 6E 08 02 00 00 06 01 00 00"));
}

TEST_CASE("hardware ids are zero-padded text", "[siyi][messages]") {
    CHECK(payload(HardwareId{"7A12345678"}) == hex("37 41 31 32 33 34 35 36 37 38 00 00"));
    CHECK(payload(HardwareId{"7A12345678901234"}).size() == 12);  // cut to its field
    const auto weird = decode_bytes<HardwareId>(hex("37 41 FF 0A 31 00 00 00 00 00 00 00"));
    REQUIRE(weird.ok());
    CHECK(to_json(weird.value)["id"] == "7A\\xFF\\x0A1");
    CHECK_NOTHROW(to_json(weird.value).dump());  // valid UTF-8 whatever the bytes
}

TEST_CASE("JSON shows enums by name and unknown values as numbers", "[siyi][messages][json]") {
    auto j = to_json(DataStreamRequest{StreamType::attitude, StreamRate::hz20});
    CHECK(j["message"] == "data_stream_request");
    CHECK(j["type"] == "attitude");
    CHECK(j["rate"] == "20hz");
    j = to_json(DataStreamRequest{static_cast<StreamType>(9), static_cast<StreamRate>(200)});
    CHECK(j["type"] == 9);
    CHECK(j["rate"] == 200);
    CHECK(to_json(FunctionFeedback{FeedbackInfo::record_started})["info"] == "record_started");
    CHECK(to_json(Center{CenterPosition::center_down})["position"] == "center_down");
    j = to_json(GimbalAttitude{-0.9, -88.0, 0, -0.3, -12.9, 0});
    CHECK(j["yaw"] == -0.9);
    CHECK(j["pitch_rate"] == -12.9);
    CHECK(j["ok"].is_null());
    CHECK(to_json(CenterReply{{false}})["ok"] == false);
}

TEST_CASE("frames render as JSON with their header, or their error", "[siyi][messages][json]") {
    const auto f = make_frame(captured_attitude_reply);
    REQUIRE(f);
    auto j = frame_to_json(*f, Direction::from_gimbal);
    CHECK(j["message"] == "gimbal_attitude");
    CHECK(j["cmd"] == 13);
    CHECK(j["ctrl"] == 2);
    CHECK(j["seq"] == 6);
    // The same bytes read as a request: 0x0D requests have no data, so this decodes too.
    CHECK(frame_to_json(*f, Direction::to_gimbal)["message"] == "gimbal_attitude_request");

    const auto short_frame = make_frame(frame_bytes(Header{}, cmd::set_gimbal_attitude, hex("01")));
    REQUIRE(short_frame);
    j = frame_to_json(*short_frame, Direction::to_gimbal);
    CHECK(j["error"] == "too_short");
    CHECK(j["length"] == 1);
    const auto unknown = make_frame(frame_bytes(Header{}, 0x7F, {}));
    CHECK(frame_to_json(*unknown, Direction::from_gimbal)["error"] == "unknown_command");
}

TEST_CASE("every message's CMD_ID dispatches to it, and names are unique", "[siyi][messages]") {
    std::vector<std::string_view> names;
    for_each_message(ToGimbalList{}, [&]<class M>(M*) {
        CAPTURE(M::name);
        const auto d = decode_to_gimbal(M::cmd, encode_payload(M{}).view());
        REQUIRE(d.ok());
        CHECK(std::holds_alternative<M>(d.value));
        CHECK(message_name(Direction::to_gimbal, M::cmd) == M::name);
        names.push_back(M::name);
    });
    for_each_message(FromGimbalList{}, [&]<class M>(M*) {
        CAPTURE(M::name);
        const auto d = decode_from_gimbal(M::cmd, encode_payload(M{}).view());
        REQUIRE(d.ok());
        CHECK(std::holds_alternative<M>(d.value));
        CHECK(message_name(Direction::from_gimbal, M::cmd) == M::name);
        names.push_back(M::name);
    });
    std::sort(names.begin(), names.end());
    CHECK(std::adjacent_find(names.begin(), names.end()) == names.end());
    CHECK(message_name(Direction::to_gimbal, 0x7F).empty());
}

TEST_CASE("random payloads decode, re-encode and decode again to the same bytes",
          "[siyi][messages][roundtrip]") {
    std::mt19937 rng(26);
    const auto check_list = [&](auto list, auto decode_fn) {
        for_each_message(list, [&]<class M>(M*) {
            CAPTURE(M::name);
            for (int n = 0; n < 200; ++n) {
                Bytes data(max_length<M>() + rng() % 3);
                for (auto& b : data) b = static_cast<std::uint8_t>(rng());
                const auto first = decode_fn(M::cmd, data);
                REQUIRE(first.ok());
                const Payload once = encode_payload(std::get<M>(first.value));
                const auto second = decode_fn(M::cmd, once.view());
                REQUIRE(second.ok());
                const Payload twice = encode_payload(std::get<M>(second.value));
                REQUIRE(Bytes(once.view().begin(), once.view().end()) ==
                        Bytes(twice.view().begin(), twice.view().end()));
                CHECK(once.size == max_length<M>());  // encoders write every field
            }
        });
    };
    check_list(ToGimbalList{}, [](std::uint8_t c, const auto& d) {
        return decode_to_gimbal(c, std::span<const std::uint8_t>(d.data(), d.size()));
    });
    check_list(FromGimbalList{}, [](std::uint8_t c, const auto& d) {
        return decode_from_gimbal(c, std::span<const std::uint8_t>(d.data(), d.size()));
    });
}

TEST_CASE("stream rate codes", "[siyi][messages]") {
    CHECK(stream_rate_hz(StreamRate::off) == 0);
    CHECK(stream_rate_hz(StreamRate::hz2) == 2);
    CHECK(stream_rate_hz(StreamRate::hz10) == 10);
    CHECK(stream_rate_hz(StreamRate::hz100) == 100);
    CHECK(stream_rate_hz(static_cast<StreamRate>(8)) == 0);
}
