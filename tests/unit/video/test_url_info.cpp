// Video URLs (contract section 17 forms), KLV packet framing for klv-udp://, and the
// stream facts an input reports (size, frame rate, bit rate).
#include <catch2/catch.hpp>

#include "ts_builder.hpp"
#include "video/klv_packets.hpp"
#include "video/stream_info.hpp"
#include "video/url.hpp"

namespace v = gimbal::video;
namespace t = gimbal::test;
using t::Bytes;

TEST_CASE("Video URLs: the forms and options, and what is refused", "[video][url]") {
    auto ok = [](std::string_view s) {
        const auto r = v::parse_video_url(s);
        INFO(s << ": " << (r ? "" : r.error().message));
        REQUIRE(r);
        return *r;
    };
    const auto in = ok("udp://0.0.0.0:15004");
    CHECK(in.scheme == v::UrlScheme::udp);
    CHECK(in.host == "0.0.0.0");
    CHECK(in.port == 15004);
    CHECK(ok("udp://:15004").host.empty());
    const auto mc = ok("udp://239.1.2.3:15004?iface=192.168.1.5&timeout_s=2.5");
    CHECK(mc.iface == "192.168.1.5");
    CHECK(mc.timeout_s == 2.5);
    CHECK(ok("udp://239.1.2.3:5000?ttl=4").ttl == 4);
    const auto v6 = ok("udp://[ff15::1]:5000");
    CHECK(v6.host == "ff15::1");
    CHECK(v6.port == 5000);
    const auto klv = ok("klv-udp://127.0.0.1:6000?ttl=1");
    CHECK(klv.scheme == v::UrlScheme::klv_udp);
    CHECK(klv.ttl == 1);
    const auto rtsp = ok("rtsp://admin:secret@10.0.0.9/live/ch0?transport=tcp&channel=1");
    CHECK(rtsp.scheme == v::UrlScheme::rtsp);
    CHECK(rtsp.host == "10.0.0.9");
    CHECK(rtsp.port == 554);
    CHECK(rtsp.transport == v::RtspTransport::tcp);
    CHECK(rtsp.rtsp_url == "rtsp://admin:secret@10.0.0.9/live/ch0?channel=1");
    const auto rtsp_port = ok("rtsp://127.0.0.1:8554/test?transport=udp&timeout_s=3");
    CHECK(rtsp_port.port == 8554);
    CHECK(rtsp_port.transport == v::RtspTransport::udp);
    CHECK(rtsp_port.timeout_s == 3.0);
    CHECK(rtsp_port.rtsp_url == "rtsp://127.0.0.1:8554/test");

    for (const char* bad :
         {"15004", "http://x:1", "udp://1.2.3.4", "udp://1.2.3.4:0", "udp://1.2.3.4:70000",
          "udp://1.2.3.4:5?ttl=0", "udp://1.2.3.4:5?ttl=300", "udp://1.2.3.4:5?bogus=1",
          "udp://ff15::1:5000", "klv-udp://:5000", "rtsp://", "rtsp://h/x?transport=sctp",
          "udp://1.2.3.4:5?timeout_s=-1", "udp://1.2.3.4:5?iface="}) {
        const auto r = v::parse_video_url(bad);
        INFO(bad);
        REQUIRE_FALSE(r);
        CHECK(r.error().code == gimbal::ErrorCode::bad_request);
        CHECK_FALSE(r.error().message.empty());
    }
}

TEST_CASE("RTSP URLs: the host:port a redirect goes to, credentials taken out or hidden",
          "[video][url]") {
    CHECK(v::rtsp_authority("rtsp://admin:secret@10.0.0.9/live") == "10.0.0.9:554");
    CHECK(v::rtsp_authority("RTSP://Camera.Local:8554/x?y=1") == "camera.local:8554");
    CHECK(v::rtsp_authority("rtsp://[fe80::1]:10554/x") == "[fe80::1]:10554");
    CHECK(v::rtsp_authority("rtsp://[fe80::1]/x") == "[fe80::1]:554");
    CHECK(v::rtsp_authority("rtsp://u:p@h") == "h:554");
    // Another port of the same host is another authority.
    CHECK(v::rtsp_authority("rtsp://10.0.0.9:555/live") != v::rtsp_authority("rtsp://10.0.0.9/"));
    for (const char* bad : {"http://10.0.0.9/x", "rtsp:///x", "rtsp://h:0/x", "rtsp://h:x/",
                            "/relative/path", "rtsp://[fe80::1/x", "rtsp://u:p@/x"}) {
        INFO(bad);
        CHECK_FALSE(v::rtsp_authority(bad));
    }
    CHECK(v::without_userinfo("rtsp://admin:secret@10.0.0.9/live?a=b") ==
          "rtsp://10.0.0.9/live?a=b");
    CHECK(v::without_userinfo("rtsp://10.0.0.9/a@b") == "rtsp://10.0.0.9/a@b");  // path, not user
    CHECK(v::redact_userinfo("rtsp://admin:secret@10.0.0.9/live") ==
          "rtsp://admin:***@10.0.0.9/live");
    CHECK(v::redact_userinfo("rtsp://admin@10.0.0.9/live") == "rtsp://admin@10.0.0.9/live");
    CHECK(v::redact_userinfo("udp://0.0.0.0:15004") == "udp://0.0.0.0:15004");
}

TEST_CASE("KLV framing: whole packets, BER long form, cut tails", "[video][klv]") {
    const Bytes a = t::klv_packet(1, 5);
    const Bytes b = t::klv_packet(2, 300);  // long form 0x82 0x01 0x2C
    Bytes both = a;
    t::put(both, b);
    std::span<const std::uint8_t> rest;
    const auto packets = v::split_klv_packets(both, &rest);
    REQUIRE(packets.size() == 2);
    CHECK(Bytes(packets[0].begin(), packets[0].end()) == a);
    CHECK(Bytes(packets[1].begin(), packets[1].end()) == b);
    CHECK(rest.empty());
    for (std::size_t cut = 0; cut < b.size(); ++cut) {
        const auto part = v::split_klv_packets(std::span(both).first(a.size() + cut), &rest);
        CHECK(part.size() == 1);
        CHECK(rest.size() == cut);
    }
    Bytes indefinite = a;
    indefinite[16] = 0x80;
    CHECK(v::split_klv_packets(indefinite).empty());
}

TEST_CASE("Stream info: size from the SPS, rate from VUI or timestamps, bit rate",
          "[video][info]") {
    v::StreamInfoTracker tracker;
    const Bytes key = t::h264_au(true);     // SPS 640x360, VUI 15 fps
    const Bytes delta = t::h264_au(false);  // no SPS
    for (int i = 0; i < 10; ++i) {
        tracker.on_bytes(1316, 100.0 + i * 0.1);
        const Bytes& d = i % 5 == 0 ? key : delta;
        tracker.on_access_unit({v::Codec::h264,
                                std::uint64_t{900000} + static_cast<std::uint64_t>(i) * 6000,
                                std::nullopt, i % 5 == 0, d});
    }
    auto info = tracker.info(101.0);
    CHECK(info.codec == v::Codec::h264);
    CHECK(info.width == 640);
    CHECK(info.height == 360);
    CHECK(info.fps == 15.0);
    CHECK(info.access_units == 10);
    CHECK(info.key_frames == 2);
    CHECK(info.bytes == 13160);
    // Arrivals at 100.1 .. 100.9 are inside the last second at 101.0: 9 x 1316 bytes.
    CHECK(info.bitrate_bps == Approx(9 * 1316 * 8));
    CHECK(tracker.info(105.0).bitrate_bps == 0);

    // No VUI timing: the median DTS step (25 fps here, with one jump ignored).
    v::StreamInfoTracker no_vui;
    Bytes au = {0, 0, 0, 1, 0x65, 0x88, 0x00};
    for (int i = 0; i < 10; ++i) {
        const std::uint64_t dts = (i < 5 ? 0 : 5'000'000) + static_cast<std::uint64_t>(i) * 3600;
        no_vui.on_access_unit({v::Codec::h264, dts + 3600, dts, false, au});
    }
    REQUIRE(no_vui.info(0).fps);
    CHECK(*no_vui.info(0).fps == Approx(25.0));
}
