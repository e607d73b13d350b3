// The video input's defences against a hostile stream (contract section 14 v4, issue 25):
// the source a UDP input takes its stream from (SourcePin, `video.source`), the worker that
// takes datagrams apart off the io thread with bounded queues, and STATE `video.klv` held to
// 8 KiB. Real loopback sockets where a socket is involved.
#include <catch2/catch.hpp>
#include <thread>

#include "config.hpp"
#include "klv/local_set.hpp"
#include "video/klv_track.hpp"
#include "video/source_pin.hpp"
#include "video/ts_worker.hpp"
#include "video/udp_ts_input.hpp"
#include "video_test_support.hpp"

namespace asio = boost::asio;
namespace gv = gimbal::video;
namespace vd = gimbald::video;
namespace klv = gimbal::klv;
using namespace video_test;
using asio::ip::udp;
using Clock = std::chrono::steady_clock;

namespace {

udp::endpoint ep(const char* address, std::uint16_t port) {
    return {asio::ip::make_address(address), port};
}

vd::SourceSpec spec(const std::string& text) {
    std::string error;
    const auto s = vd::parse_source(text, error);
    INFO(error);
    REQUIRE(s);
    return *s;
}

gv::VideoUrl url(const std::string& text) {
    const auto r = gv::parse_video_url(text);
    REQUIRE(r);
    return *r;
}

// A valid set of about `bytes` bytes: a position, then unknown tags of 48 bytes each.
Bytes big_set(std::size_t bytes) {
    klv::LocalSet set;
    set.add(klv::tag_of("precision_time_stamp"), std::uint64_t{1'700'000'000'000'000});
    set.add(klv::tag_of("sensor_latitude"), 45.5);
    set.add(klv::tag_of("sensor_longitude"), -121.25);
    for (std::uint32_t tag = 200; tag < 200 + bytes / 51; ++tag) set.add(tag, Bytes(48, 0xEE));
    const auto e = klv::encode(set);
    REQUIRE(e.ok());
    return *e;
}

}  // namespace

TEST_CASE("video source: parse_source takes numeric ADDR[:PORT] only", "[video][source]") {
    CHECK(spec("10.0.0.5") == vd::SourceSpec{asio::ip::make_address("10.0.0.5"), std::nullopt});
    CHECK(spec("10.0.0.5:5004").port == 5004);
    CHECK(spec("[fe80::1]:5004").port == 5004);
    CHECK(spec("[::1]").address == asio::ip::make_address("::1"));
    CHECK(spec("::1").address == asio::ip::make_address("::1"));
    std::string error;
    for (const char* bad : {"", "camera.local", "10.0.0.5:0", "10.0.0.5:70000", "10.0.0.5:", "[::1",
                            "[::1]x", "10.0.0.5:abc"}) {
        INFO(bad);
        CHECK_FALSE(vd::parse_source(bad, error));
    }
}

TEST_CASE("gimbals[].video.source: read and checked", "[video][source][config]") {
    const auto read = [](const nlohmann::json& video) {
        nlohmann::json c = {{"gimbals",
                             {{{"name", "a"},
                               {"protocol", "orion"},
                               {"link", {{"type", "sim"}}},
                               {"video", video}}}}};
        return gimbal::daemon::parse_config(c.dump());
    };
    const auto texts = [](const gimbal::daemon::ConfigResult& r) {
        std::vector<std::string> out;
        for (const auto& p : r.problems) out.push_back(p.text());
        return out;
    };
    const auto ok = read({{"input", "udp://0.0.0.0:15004"}, {"source", "10.0.0.5:5004"}});
    REQUIRE(ok.ok());
    CHECK(ok.config.gimbals[0].video->source == "10.0.0.5:5004");
    const auto none = read({{"input", "udp://0.0.0.0:15004"}, {"source", nullptr}});
    REQUIRE(none.ok());
    CHECK_FALSE(none.config.gimbals[0].video->source);
    CHECK(texts(read({{"input", "udp://0.0.0.0:15004"}, {"source", "camera.local"}})) ==
          std::vector<std::string>{
              "gimbals[0].video.source: \"camera.local\": \"camera.local\" is not a numeric "
              "IP address"});
    CHECK(texts(read({{"input", "udp://0.0.0.0:15004"}, {"source", 5004}})) ==
          std::vector<std::string>{
              "gimbals[0].video.source: must be a string \"ADDR[:PORT]\" or null"});
    CHECK(texts(read({{"input", "rtsp://10.0.0.5/live"}, {"source", "10.0.0.5"}})) ==
          std::vector<std::string>{"gimbals[0].video.source: only for a udp:// input (an RTSP "
                                   "input names its camera)"});
}

TEST_CASE("video source: the first sender is pinned until silent for 5 s", "[video][source]") {
    vd::SourcePin pin(std::nullopt);
    const auto t0 = Clock::now();
    using V = vd::SourcePin::Verdict;
    CHECK(pin.check(ep("10.0.0.5", 5000), t0) == V::pinned);
    CHECK(pin.check(ep("10.0.0.5", 5000), t0 + 1s) == V::accepted);
    CHECK(pin.check(ep("10.0.0.6", 5000), t0 + 2s) == V::foreign);
    CHECK(pin.check(ep("10.0.0.5", 5001), t0 + 3s) == V::foreign);  // another port: another sender
    CHECK(pin.check(ep("10.0.0.5", 5000), t0 + 5s) == V::accepted);
    CHECK(pin.foreign() == 2);
    // Silent for 5 s: the next sender is taken.
    CHECK(pin.check(ep("10.0.0.6", 5000), t0 + 9s) == V::foreign);
    CHECK(pin.check(ep("10.0.0.6", 5000), t0 + 10s) == V::pinned);
    CHECK(pin.current() == ep("10.0.0.6", 5000));
    CHECK(pin.check(ep("10.0.0.5", 5000), t0 + 10500ms) == V::foreign);
    // An IPv4 sender seen through a dual-stack socket is the same sender.
    CHECK(pin.check(ep("::ffff:10.0.0.6", 5000), t0 + 11s) == V::accepted);
}

TEST_CASE("video source: a configured source is the only one taken", "[video][source]") {
    using V = vd::SourcePin::Verdict;
    const auto t0 = Clock::now();
    vd::SourcePin any_port(spec("10.0.0.5"));
    CHECK(any_port.check(ep("10.0.0.6", 5000), t0) == V::foreign);
    CHECK(any_port.check(ep("10.0.0.5", 5000), t0) == V::accepted);
    CHECK(any_port.check(ep("10.0.0.5", 6000), t0) == V::accepted);
    CHECK(any_port.check(ep("10.0.0.6", 5000), t0 + 60s) == V::foreign);  // silence changes nothing
    CHECK(any_port.foreign() == 2);
    vd::SourcePin one_port(spec("10.0.0.5:5000"));
    CHECK(one_port.check(ep("10.0.0.5", 5001), t0) == V::foreign);
    CHECK(one_port.check(ep("10.0.0.5", 5000), t0) == V::accepted);
}

TEST_CASE("video udp input: datagrams from another sender are counted, not used",
          "[video][udp][source]") {
    asio::io_context io;
    const std::uint16_t port = free_udp_port();
    std::vector<gv::AccessUnitBuffer> units;
    std::vector<Bytes> sets;
    vd::VideoInputHandlers handlers;
    handlers.access_unit = [&](const gv::AccessUnit& au, vd::Clock::time_point) {
        units.emplace_back(au);
    };
    handlers.klv = [&](klv::CheckedSets& c, vd::Clock::time_point) {
        for (const auto& s : c.sets) sets.push_back(s.bytes);
    };
    vd::UdpTsInput input(io, url("udp://127.0.0.1:" + std::to_string(port)), {},
                         std::move(handlers));
    input.start();
    const udp::endpoint to(asio::ip::make_address("127.0.0.1"), port);
    asio::io_context senders;
    udp::socket camera(senders, udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    udp::socket stranger(senders, udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    const TestStream real(10);
    const TestStream fake(10);
    camera.send_to(asio::buffer(real.datagrams[0]), to);
    REQUIRE(run_until(io, [&] { return !input.status().source.empty(); }));
    for (std::size_t i = 1; i < real.datagrams.size(); ++i) {
        camera.send_to(asio::buffer(real.datagrams[i]), to);
        stranger.send_to(asio::buffer(fake.datagrams[i % fake.datagrams.size()]), to);
    }
    REQUIRE(run_until(io, [&] { return units.size() == 10 && sets.size() == 10; }));
    run_for(io, 100ms);
    CHECK(units.size() == 10);
    CHECK(sets == real.klv);
    const auto st = input.status();
    CHECK(st.source == vd::to_string(camera.local_endpoint()));
    CHECK(st.foreign_datagrams == real.datagrams.size() - 1);
    CHECK(st.demux.cc_errors == 0);  // the stranger's packets never reached the demuxer
}

TEST_CASE("video udp input: a configured source that never sends gives nothing",
          "[video][udp][source]") {
    asio::io_context io;
    const std::uint16_t port = free_udp_port();
    std::size_t units = 0;
    vd::VideoInputHandlers handlers;
    handlers.access_unit = [&](const gv::AccessUnit&, vd::Clock::time_point) { ++units; };
    vd::VideoInputOptions options;
    options.source = spec("127.0.0.2");
    vd::UdpTsInput input(io, url("udp://127.0.0.1:" + std::to_string(port)), options,
                         std::move(handlers));
    input.start();
    const TestStream stream(5);
    asio::io_context senders;
    udp::socket s(senders, udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    for (const Bytes& d : stream.datagrams)
        s.send_to(asio::buffer(d), udp::endpoint(asio::ip::make_address("127.0.0.1"), port));
    REQUIRE(
        run_until(io, [&] { return input.status().foreign_datagrams == stream.datagrams.size(); }));
    CHECK(units == 0);
    CHECK_FALSE(input.status().connected);
    CHECK(input.status().source.empty());
}

TEST_CASE("video ts worker: demuxing runs off the io thread, what waits is bounded and counted",
          "[video][worker]") {
    asio::io_context io;
    const auto io_thread = std::this_thread::get_id();
    std::vector<gv::AccessUnitBuffer> units;
    std::vector<Bytes> sets;
    bool batch_on_io = true;
    vd::TsWorkerOptions options;
    options.max_batches = 4;
    vd::TsWorker worker(io, options, [&](vd::TsBatch& b) {
        batch_on_io = batch_on_io && std::this_thread::get_id() == io_thread;
        for (auto& u : b.units) units.push_back(std::move(u));
        for (auto& s : b.klv.sets) sets.push_back(std::move(s.bytes));
    });
    const TestStream stream(40);
    const auto now = Clock::now();
    // The io thread does not run while the datagrams are handed over: at most 4 batches wait.
    for (const Bytes& d : stream.datagrams) worker.push(d, now);
    const auto all_taken = [&] {
        const auto c = worker.counters();
        return c.demux.bytes == [&] {
            std::uint64_t n = 0;
            for (const Bytes& d : stream.datagrams) n += d.size();
            return n;
        }();
    };
    const auto deadline = Clock::now() + 5s;
    while (!all_taken() && Clock::now() < deadline) std::this_thread::sleep_for(1ms);
    REQUIRE(all_taken());
    run_for(io, 100ms);
    CHECK(batch_on_io);
    const auto c = worker.counters();
    CHECK(c.demux.access_units == 40);
    CHECK(c.dropped_units > 0);
    CHECK(units.size() + c.dropped_units == 40);
    CHECK(sets.size() + c.dropped_klv_sets == 40);
    CHECK(units.size() <= 4 * 2);
}

TEST_CASE("video ts worker: the access units waiting on the io thread are bounded in bytes",
          "[video][worker]") {
    asio::io_context io;
    std::size_t units = 0;
    vd::TsWorkerOptions options;
    options.max_unit_bytes = 64 * 1024;  // about ten of the stream's units
    vd::TsWorker worker(io, options, [&](vd::TsBatch& b) { units += b.units.size(); });
    const TestStream stream(40, 6000);
    for (const Bytes& d : stream.datagrams) worker.push(d, Clock::now());
    const auto deadline = Clock::now() + 5s;
    while (worker.counters().demux.access_units < 40 && Clock::now() < deadline)
        std::this_thread::sleep_for(1ms);
    run_for(io, 100ms);
    const auto c = worker.counters();
    CHECK(c.dropped_units > 0);
    CHECK(units + c.dropped_units == 40);
    CHECK(units <= 12);
}

TEST_CASE("video klv: STATE's klv holds at most 8 KiB of JSON", "[video][klv]") {
    // A valid 46 KB set (the review's, which made STATE 165 KB) as a UDP input delivers it.
    const Bytes set = big_set(46'000);
    REQUIRE(set.size() > 40'000);
    klv::CheckLimits limits;
    limits.max_json_bytes = vd::KlvTrack::max_json_bytes;
    klv::CheckedSets checked = klv::check_sets(set, limits);
    REQUIRE(checked.sets.size() == 1);
    CHECK(checked.sets[0].truncated);
    vd::KlvTrack track;
    track.stream_sets(std::move(checked), 1.0);
    nlohmann::json shown = track.latest_json();
    shown["age_s"] = 123456.789;
    CHECK(shown.dump().size() <= vd::KlvTrack::max_state_json_bytes);
    CHECK(shown["sensor_latitude"] == 45.5);
    CHECK(shown["truncated"] == true);
    CHECK(track.latest_bytes()->size() == set.size());  // the bytes relayed stay whole
    CHECK(track.sets() == 1);
}
