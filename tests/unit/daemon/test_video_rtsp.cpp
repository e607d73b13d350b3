// The RTSP input against a real RTSP server (GStreamer's, tests/integration/rtsp_server.py):
// H.264 over RTP on TCP and on UDP gives access units with SPS/PPS before key frames, the
// codec and the size; a stop while blocked connecting returns within a second; a server
// that goes away is reported and retried.
#include <catch2/catch.hpp>
#include <thread>

#include <boost/asio/ip/tcp.hpp>

#include "video/nal.hpp"
#include "video/rtsp_input.hpp"
#include "video_test_support.hpp"

namespace asio = boost::asio;
namespace gv = gimbal::video;
namespace vd = gimbald::video;
using namespace video_test;

namespace {

gv::VideoUrl url(const std::string& text) {
    const auto r = gv::parse_video_url(text);
    INFO((r ? "" : r.error().message));
    REQUIRE(r);
    return *r;
}

struct Received {
    std::vector<gv::AccessUnitBuffer> units;
    std::vector<bool> connections;
    vd::VideoInputHandlers handlers() {
        return {[this](const gv::AccessUnit& au, vd::Clock::time_point) { units.emplace_back(au); },
                {},
                [this](bool up) { connections.push_back(up); },
                {}};
    }
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST_CASE("video rtsp input: H.264 over TCP and UDP from GStreamer's RTSP server",
          "[video][rtsp]") {
    RtspServer server({"--width", "320", "--height", "240", "--fps", "15"});
    REQUIRE(server.port() != 0);
    for (const char* transport : {"tcp", "udp"}) {
        SECTION(transport) {
            asio::io_context io;
            Received got;
            vd::RtspInput input(io,
                                url("rtsp://127.0.0.1:" + std::to_string(server.port()) +
                                    "/test?transport=" + transport),
                                {}, got.handlers());
            input.start();
            REQUIRE(run_until(
                io, [&] { return got.units.size() >= 20; }, 15000ms));
            const auto st = input.status();
            CHECK(st.connected);
            CHECK(got.connections.front());
            CHECK(st.stream.codec == gv::Codec::h264);
            CHECK(st.stream.width == 320);
            CHECK(st.stream.height == 240);
            REQUIRE(st.stream.fps);
            CHECK(*st.stream.fps == Approx(15.0).margin(0.5));
            CHECK(st.stream.bitrate_bps > 0);
            // Every key frame carries SPS and PPS before its slice; timestamps advance.
            int keys = 0;
            for (const auto& u : got.units) {
                CHECK(u.codec == gv::Codec::h264);
                REQUIRE(u.pts);
                if (!u.key_frame) continue;
                ++keys;
                bool sps = false, pps = false;
                for (const auto nal : gv::split_annexb(u.data)) {
                    const auto t = gv::nal_type(gv::Codec::h264, nal);
                    sps = sps || t == gv::h264::sps;
                    pps = pps || t == gv::h264::pps;
                    if (gv::is_vcl(gv::Codec::h264, t)) break;
                }
                CHECK(sps);
                CHECK(pps);
                CHECK(gv::find_format(gv::Codec::h264, u.data) ==
                      gv::VideoFormat{320, 240, st.stream.fps});
            }
            CHECK(keys >= 1);
            for (std::size_t i = 1; i < got.units.size(); ++i)
                CHECK(*got.units[i].pts > *got.units[i - 1].pts);
            const auto t0 = std::chrono::steady_clock::now();
            input.stop();
            CHECK(seconds_since(t0) < 1.0);
            const auto n = got.units.size();
            run_for(io, 100ms);
            CHECK(got.units.size() == n);  // nothing after stop()
        }
    }
}

TEST_CASE("video rtsp input: stop while blocked on a silent server returns within a second",
          "[video][rtsp]") {
    asio::io_context io;
    // Accepts TCP connections (the backlog does) and never answers a request.
    asio::ip::tcp::acceptor silent(io, {asio::ip::address_v4::loopback(), 0});
    Received got;
    vd::RtspInput input(io,
                        url("rtsp://127.0.0.1:" + std::to_string(silent.local_endpoint().port()) +
                            "/x?timeout_s=30"),
                        {}, got.handlers());
    input.start();
    std::this_thread::sleep_for(300ms);
    const auto t0 = std::chrono::steady_clock::now();
    input.stop();
    CHECK(seconds_since(t0) < 1.0);
    run_for(io, 50ms);
    CHECK(got.units.empty());
    CHECK_FALSE(input.status().connected);
}

TEST_CASE("video rtsp input: a server that goes away is reported and retried", "[video][rtsp]") {
    RtspServer server;
    REQUIRE(server.port() != 0);
    asio::io_context io;
    Received got;
    vd::VideoInputOptions options;
    options.timeout_s = 1.0;
    options.backoff = {0.1, 0.3, 0.0};
    vd::RtspInput input(io, url("rtsp://127.0.0.1:" + std::to_string(server.port()) + "/test"),
                        options, got.handlers());
    input.start();
    REQUIRE(run_until(
        io, [&] { return !got.units.empty(); }, 15000ms));
    server.kill_now();
    REQUIRE(run_until(
        io, [&] { return got.connections.size() >= 2; }, 5000ms));
    CHECK(got.connections[0]);
    CHECK_FALSE(got.connections[1]);
    REQUIRE(run_until(
        io, [&] { return input.status().reconnects >= 2; }, 5000ms));
    const auto st = input.status();
    CHECK_FALSE(st.connected);
    CHECK_FALSE(st.last_error.empty());
    input.stop();
}

TEST_CASE("video rtsp input: H.265 over TCP", "[video][rtsp]") {
    RtspServer server({"--codec", "h265", "--width", "352", "--height", "288", "--fps", "10"});
    REQUIRE(server.port() != 0);
    asio::io_context io;
    Received got;
    vd::RtspInput input(
        io, url("rtsp://127.0.0.1:" + std::to_string(server.port()) + "/test?transport=tcp"), {},
        got.handlers());
    input.start();
    REQUIRE(run_until(
        io, [&] { return got.units.size() >= 10; }, 15000ms));
    const auto st = input.status();
    CHECK(st.stream.codec == gv::Codec::h265);
    CHECK(st.stream.width == 352);
    CHECK(st.stream.height == 288);
    const auto key =
        std::find_if(got.units.begin(), got.units.end(), [](const auto& u) { return u.key_frame; });
    REQUIRE(key != got.units.end());
    bool vps = false, sps = false, pps = false;
    for (const auto nal : gv::split_annexb(key->data)) {
        const auto t = gv::nal_type(gv::Codec::h265, nal);
        vps = vps || t == gv::h265::vps;
        sps = sps || t == gv::h265::sps;
        pps = pps || t == gv::h265::pps;
    }
    CHECK(vps);
    CHECK(sps);
    CHECK(pps);
    input.stop();
}
