// daemon/video over real loopback sockets: the UDP TS input (unicast, multicast join), the
// MPEG-TS and klv-udp outputs, and an output with no route that must not block.
#include <fcntl.h>
#include <net/if.h>
#include <sched.h>
#include <sys/ioctl.h>

#include <catch2/catch.hpp>
#include <thread>

#include "../video/demux_collector.hpp"
#include "video/udp_ts_input.hpp"
#include "video/video_output.hpp"
#include "video_test_support.hpp"

namespace asio = boost::asio;
namespace gv = gimbal::video;
namespace vd = gimbald::video;
using namespace video_test;

namespace {

struct Received {
    std::vector<gv::AccessUnitBuffer> units;
    std::vector<Bytes> klv;
    std::vector<bool> connections;
    std::size_t ts_bytes = 0;
    std::uint64_t bad_checksums = 0;
    std::uint64_t refused = 0;

    vd::VideoInputHandlers handlers() {
        return {[this](const gv::AccessUnit& au, vd::Clock::time_point) { units.emplace_back(au); },
                [this](gimbal::klv::CheckedSets& checked, vd::Clock::time_point) {
                    for (const auto& set : checked.sets) klv.push_back(set.bytes);
                    bad_checksums += checked.bad_checksums;
                    refused += checked.refused;
                },
                [this](bool up) { connections.push_back(up); },
                [this](std::span<const std::uint8_t> b, vd::Clock::time_point) {
                    ts_bytes += b.size();
                }};
    }
};

gv::VideoUrl url(const std::string& text) {
    const auto r = gv::parse_video_url(text);
    INFO((r ? "" : r.error().message));
    REQUIRE(r);
    return *r;
}

void send_all(const std::vector<Bytes>& datagrams, const asio::ip::udp::endpoint& to) {
    asio::io_context io;
    asio::ip::udp::socket s(io, asio::ip::udp::v4());
    for (const Bytes& d : datagrams) s.send_to(asio::buffer(d), to);
}

}  // namespace

TEST_CASE("video udp input: a TS from a loopback socket gives its access units and KLV",
          "[video][udp]") {
    asio::io_context io;
    const std::uint16_t port = free_udp_port();
    Received got;
    vd::VideoInputOptions options;
    options.timeout_s = 0.3;
    options.source_silence_s = 0.1;  // send_all() sends from a new socket each time
    vd::UdpTsInput input(io, url("udp://127.0.0.1:" + std::to_string(port)), options,
                         got.handlers());
    input.start();
    REQUIRE(input.local_port() == port);
    const TestStream stream(30);
    send_all(stream.datagrams, {asio::ip::make_address("127.0.0.1"), port});
    REQUIRE(run_until(io, [&] { return got.units.size() == 30 && got.klv.size() == 30; }));
    for (std::size_t i = 0; i < 30; ++i)
        CHECK(gimbal::test::same_unit(got.units[i], stream.units[i]));
    CHECK(got.klv == stream.klv);
    std::size_t total = 0;
    for (const Bytes& d : stream.datagrams) total += d.size();
    CHECK(got.ts_bytes == total);
    auto st = input.status();
    CHECK(st.connected);
    CHECK(st.stream.codec == gv::Codec::h264);
    CHECK(st.stream.width == 640);
    CHECK(st.stream.height == 360);
    CHECK(st.stream.fps == 15.0);  // the SPS's VUI says 15 (the test stream's timestamps say 30)
    CHECK(st.stream.bitrate_bps > 0);
    CHECK(st.klv == gv::KlvCarriage::async);
    CHECK(st.demux.cc_errors == 0);
    REQUIRE(got.connections == std::vector<bool>{true});
    // Silence: disconnected after timeout_s; data again: connected.
    REQUIRE(run_until(
        io, [&] { return got.connections.size() == 2; }, 2000ms));
    CHECK_FALSE(got.connections[1]);
    CHECK_FALSE(input.status().connected);
    send_all({stream.datagrams[0]}, {asio::ip::make_address("127.0.0.1"), port});
    REQUIRE(run_until(
        io, [&] { return got.connections.size() == 3; }, 2000ms));
    CHECK(got.connections[2]);
    input.stop();
    // After stop() nothing more arrives.
    send_all(stream.datagrams, {asio::ip::make_address("127.0.0.1"), port});
    const auto before = got.units.size();
    run_for(io, 200ms);
    CHECK(got.units.size() == before);
}

TEST_CASE("video udp input and output: multicast on loopback with a TTL",
          "[video][udp][multicast]") {
    asio::io_context io;
    const std::uint16_t port = free_udp_port();
    const std::string group = "239.255.71.3:" + std::to_string(port);
    Received got;
    vd::UdpTsInput input(io, url("udp://" + group + "?iface=127.0.0.1"), {}, got.handlers());
    REQUIRE(input.multicast());
    input.start();
    run_for(io, 50ms);
    if (!input.status().last_error.empty()) {
        WARN("multicast join not possible here, skipped: " << input.status().last_error);
        return;
    }
    auto output = vd::make_video_output(io, url("udp://" + group + "?ttl=1&iface=127.0.0.1"));
    const TestStream stream(20);
    for (const auto& u : stream.units) output->write_video(u.view());
    if (!run_until(
            io, [&] { return got.units.size() == 20; }, 2000ms) &&
        got.units.empty()) {
        WARN("multicast on loopback delivers nothing here, skipped (sent "
             << output->stats().datagrams << ", error '" << output->stats().last_error << "')");
        return;
    }
    REQUIRE(got.units.size() == 20);
    for (std::size_t i = 0; i < 20; ++i) CHECK(got.units[i].data == stream.units[i].data);
    CHECK(output->stats().errors == 0);
}

TEST_CASE("video outputs: MPEG-TS datagrams and klv-udp sets to a loopback receiver",
          "[video][udp]") {
    asio::io_context io;
    asio::ip::udp::socket rx(io, {asio::ip::address_v4::loopback(), 0});
    const auto port = rx.local_endpoint().port();
    auto ts = vd::make_video_output(io, url("udp://127.0.0.1:" + std::to_string(port) + "?ttl=3"));
    const TestStream stream(12, 5000);
    for (std::size_t i = 0; i < stream.units.size(); ++i) {
        ts->write_video(stream.units[i].view());
        ts->write_klv(stream.klv[i], stream.units[i].pts);
    }
    gimbal::test::Collector c;
    gv::TsDemuxer demux(c.handlers());
    std::array<std::uint8_t, 65536> buf{};
    rx.non_blocking(true);
    std::size_t datagrams = 0;
    for (;;) {
        boost::system::error_code ec;
        const std::size_t n = rx.receive(asio::buffer(buf), 0, ec);
        if (ec) break;
        ++datagrams;
        CHECK(n % 188 == 0);
        CHECK(n <= 1316);
        demux.push(std::span(buf.data(), n));
    }
    CHECK(datagrams == ts->stats().datagrams);
    REQUIRE(c.units.size() == stream.units.size());
    for (std::size_t i = 0; i < c.units.size(); ++i)
        CHECK(gimbal::test::same_unit(c.units[i], stream.units[i]));
    CHECK(c.klv.size() == stream.klv.size());

    auto klv = vd::make_video_output(io, url("klv-udp://127.0.0.1:" + std::to_string(port)));
    Bytes two = stream.klv[0];
    two.insert(two.end(), stream.klv[1].begin(), stream.klv[1].end());
    klv->write_klv(two, std::nullopt);
    klv->write_video(stream.units[0].view());  // ignored
    std::vector<Bytes> sets;
    for (;;) {
        boost::system::error_code ec;
        const std::size_t n = rx.receive(asio::buffer(buf), 0, ec);
        if (ec) break;
        sets.emplace_back(buf.begin(), buf.begin() + static_cast<long>(n));
    }
    REQUIRE(sets.size() == 2);
    CHECK(sets[0] == stream.klv[0]);
    CHECK(sets[1] == stream.klv[1]);
    CHECK_THROWS_AS(vd::make_video_output(io, url("rtsp://127.0.0.1/x")), std::invalid_argument);
    CHECK_THROWS_AS(vd::make_video_output(io, url("udp://example.org:5000")),
                    std::invalid_argument);
}

namespace {

// Runs in a child in its own network namespace, where nothing is routable until lo comes up.
// Exit codes: 0 passed, 77 no namespace (not root), 10+ the check that failed.
int no_route_child() {
    if (unshare(CLONE_NEWNET) != 0) return 77;
    asio::io_context io;
    vd::VideoOutputOptions options;
    options.retry_s = 0.05;
    const std::uint16_t port = 15010;
    auto out = vd::make_video_output(io, url("udp://127.0.0.1:" + std::to_string(port)), options);
    const TestStream stream(300, 20000);  // 10 s of video, ~16 datagrams a frame
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& u : stream.units) out->write_video(u.view());
    const auto took = std::chrono::steady_clock::now() - t0;
    if (took > 1s) return 10;                    // never blocks
    if (out->stats().datagrams != 0) return 11;  // nothing can go out
    if (out->stats().errors == 0) return 12;     // the failure was seen
    if (out->stats().errors > 5) return 13;      // and sends paused, not retried per datagram
    // The route appears (lo up): after retry_s the output sends again.
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    ifreq ifr{};
    std::snprintf(ifr.ifr_name, IFNAMSIZ, "lo");
    if (ioctl(fd, SIOCGIFFLAGS, &ifr) != 0) return 14;
    ifr.ifr_flags = static_cast<short>(ifr.ifr_flags | IFF_UP);
    if (ioctl(fd, SIOCSIFFLAGS, &ifr) != 0) return 15;
    close(fd);
    asio::ip::udp::socket rx(io, {asio::ip::address_v4::loopback(), port});
    std::this_thread::sleep_for(100ms);
    for (int i = 0; i < 3; ++i) out->write_video(stream.units[static_cast<std::size_t>(i)].view());
    if (out->stats().datagrams == 0) return 16;
    rx.non_blocking(true);
    std::array<std::uint8_t, 2048> buf{};
    boost::system::error_code ec;
    if (rx.receive(asio::buffer(buf), 0, ec) == 0 || ec) return 17;
    return 0;
}

}  // namespace

TEST_CASE("video output: no route does not block, is counted, and is retried", "[video][udp]") {
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) _exit(no_route_child());
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    REQUIRE(WIFEXITED(status));
    const int code = WEXITSTATUS(status);
    if (code == 77) {
        WARN("no network namespace (needs root), skipped");
        return;
    }
    CHECK(code == 0);
}
