// Every example frame of SIYI's documents (vectors.hpp) frames, decodes to the values its
// caption gives, and re-encodes byte for byte.
#include <catch2/catch.hpp>

#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "vectors.hpp"

using namespace gimbal::siyi;
using namespace siyi_test;

namespace {

template <class M>
M request(const Bytes& bytes) {
    const auto frame = make_frame(bytes);
    REQUIRE(frame);
    const auto d = decode_to_gimbal(*frame);
    REQUIRE(d.ok());
    REQUIRE(std::holds_alternative<M>(d.value));
    return std::get<M>(d.value);
}

const Bytes& sdk(std::string_view what) {
    for (const Golden& g : sdk_requests())
        if (g.what == what) return g.bytes;
    FAIL("no golden frame " << what);
    static const Bytes none;
    return none;
}

}  // namespace

TEST_CASE("SDK example requests decode and re-encode byte for byte", "[siyi][golden]") {
    for (const Golden& g : sdk_requests()) {
        if (g.source == "SDK-old") continue;  // their layout is older (below)
        CAPTURE(g.what);
        const auto frame = make_frame(g.bytes);
        REQUIRE(frame);
        CHECK(frame->ctrl == ctrl_need_ack);
        const auto d = decode_to_gimbal(*frame);
        REQUIRE(d.ok());
        CHECK(command_of(d.value) == frame->cmd);
        CHECK(encode(d.value, Header{frame->ctrl, frame->seq}) == g.bytes);
    }
}

TEST_CASE("SDK example requests carry the values their captions give", "[siyi][golden]") {
    CHECK(std::holds_alternative<TcpHeartbeat>(
        decode_to_gimbal(*make_frame(sdk("TCP heartbeat"))).value));
    CHECK(request<ManualZoom>(sdk("zoom 1")).zoom == ZoomStep::in);
    CHECK(request<ManualZoom>(sdk("zoom -1")).zoom == ZoomStep::out);
    CHECK(request<ManualFocus>(sdk("focus 1")).focus == FocusStep::far);
    CHECK(request<ManualFocus>(sdk("focus -1")).focus == FocusStep::near);

    const auto zoom_frame = make_frame(sdk("Absolute Zoom (4.5x)"));
    CHECK(zoom_frame->seq == 1);
    CHECK(request<AbsoluteZoom>(sdk("Absolute Zoom (4.5x)")).zoom == Approx(4.5));

    CHECK(request<Capture>(sdk("Take Photo")).function == CaptureFunction::take_photo);
    CHECK(request<Capture>(sdk("Start Video Recording")).function ==
          CaptureFunction::record_toggle);
    CHECK(request<Capture>(sdk("Lock Mode")).function == CaptureFunction::lock_mode);
    CHECK(request<Capture>(sdk("Follow Mode")).function == CaptureFunction::follow_mode);
    CHECK(request<Capture>(sdk("FPV Mode")).function == CaptureFunction::fpv_mode);
    CHECK(request<Capture>(sdk("Set HDMI Video Output")).function == CaptureFunction::hdmi_output);
    CHECK(request<Capture>(sdk("Disable CVBS and HDMI Output")).function ==
          CaptureFunction::video_output_off);

    const auto rot = request<GimbalRotation>(sdk("Pan/Tilt 100 100"));
    CHECK(rot.turn_yaw == 100);
    CHECK(rot.turn_pitch == 100);

    const auto af = request<AutoFocus>(sdk("Auto Focus"));
    CHECK(af.trigger);
    CHECK(af.touch_x == 300);
    CHECK(af.touch_y == 100);

    CHECK(request<Center>(sdk("One-Key Centering")).position == CenterPosition::one_key_center);

    const auto down =
        request<SetGimbalAttitude>(sdk("Set Gimbal Control Angle (-90, 0) (Facing Down)"));
    CHECK(down.yaw == 0.0);
    CHECK(down.pitch == -90.0);

    const auto gps = request<RawGps>(sdk("Send GPS Coordinates"));
    CHECK(gps.time_boot_ms == 0);
    CHECK(gps.lat == Approx(22.27683).margin(1e-9));
    CHECK(gps.lon == Approx(114.17612).margin(1e-9));
    CHECK(gps.alt_msl == 0.0);
    CHECK(gps.vd == 0.0);

    // The requests without data.
    CHECK(request<CameraSystemInfoRequest>(sdk("Gimbal Status Information")).cmd == 0x0A);
    CHECK(request<HardwareIdRequest>(sdk("Retrieve Hardware ID")).cmd == 0x02);
    CHECK(request<FirmwareVersionRequest>(sdk("Retrieve Firmware Version")).cmd == 0x01);
    CHECK(request<GimbalAttitudeRequest>(sdk("Retrieve Attitude Data")).cmd == 0x0D);
    CHECK(request<LaserDistanceRequest>(sdk("Read Laser Ranging Distance")).cmd == 0x15);
    CHECK(request<ZoomRangeRequest>(sdk("Retrieve Maximum Zoom Value in Current State")).cmd ==
          0x16);
    CHECK(request<CurrentZoomRequest>(sdk("Retrieve Current Zoom Value")).cmd == 0x18);
    CHECK(request<GimbalModeRequest>(sdk("Retrieve Current Gimbal Mode")).cmd == 0x19);
}

TEST_CASE("older SDK examples decode, and the encoder writes today's layout", "[siyi][golden]") {
    // Earlier editions sent auto focus as one byte: the touch point is an optional tail.
    const auto af = request<AutoFocus>(sdk("Auto Focus (one byte)"));
    CHECK(af.trigger);
    CHECK(af.touch_x == 0);
    CHECK(af.touch_y == 0);
    CHECK(encode(af, Header{}).size() == frame_overhead + 5);

    const auto rot = request<GimbalRotation>(sdk("Gimbal Speed (32, 32)"));
    CHECK(rot.turn_yaw == 32);
    CHECK(rot.turn_pitch == 32);
    CHECK(encode(rot, Header{}) == sdk("Gimbal Speed (32, 32)"));
}

TEST_CASE("SDK examples of commands gimbald does not declare frame and decode as unknown",
          "[siyi][golden]") {
    for (const Golden& g : sdk_undeclared()) {
        CAPTURE(g.what);
        const auto frame = make_frame(g.bytes);
        REQUIRE(frame);
        CHECK(decode_to_gimbal(*frame).error == DecodeError::unknown_command);
        CHECK(frame_bytes(*frame) == g.bytes);
    }
}

TEST_CASE("a documented reply frames with ack_pack and the device's sequence", "[siyi][golden]") {
    const auto frame = make_frame(mk15_hardware_id_reply);
    REQUIRE(frame);
    CHECK(frame->is_ack());
    CHECK_FALSE(frame->need_ack());
    CHECK(frame->seq == 9);
    CHECK(frame->cmd == 0x40);  // the datalink's own command: not a gimbal message
    CHECK(decode_from_gimbal(*frame).error == DecodeError::unknown_command);
    // Its data has the layout of the gimbal's 0x02 reply: ten digits in twelve bytes.
    const auto id = decode<HardwareId>(frame->data.view());
    REQUIRE(id.ok());
    CHECK(id.value.id == "6801130111");
    CHECK(encode(id.value, Header{frame->ctrl, frame->seq}).size() ==
          mk15_hardware_id_reply.size());
}

TEST_CASE("attitude replies recorded from cameras decode", "[siyi][golden]") {
    const auto frame = make_frame(captured_attitude_reply);
    REQUIRE(frame);
    CHECK(frame->ctrl == ctrl_ack_pack);
    CHECK(frame->seq == 6);
    const auto d = decode_from_gimbal(*frame);
    REQUIRE(d.ok());
    const auto& a = std::get<GimbalAttitude>(d.value);
    CHECK(a.yaw == Approx(-0.9));
    CHECK(a.pitch == Approx(-88.0));
    CHECK(a.roll == 0.0);
    CHECK(a.yaw_rate == Approx(-0.3));
    CHECK(a.pitch_rate == Approx(-12.9));
    CHECK(a.roll_rate == 0.0);
    CHECK(encode(d.value, Header{frame->ctrl, frame->seq}) == captured_attitude_reply);

    const auto f2 = make_frame(captured_attitude_reply2);
    REQUIRE(f2);
    const auto a2 = std::get<GimbalAttitude>(decode_from_gimbal(*f2).value);
    CHECK(a2.yaw == Approx(2.6));
    CHECK(a2.pitch == Approx(-179.9));
    CHECK(encode(a2, Header{f2->ctrl, f2->seq}) == captured_attitude_reply2);
}
