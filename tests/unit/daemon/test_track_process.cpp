// gimbal-track's supervisor (daemon/track/track_process.hpp) with stand-in programs: one that
// exits at once is started again and again with a growing delay; one that never says hello is
// killed and started again; nothing is sent to a process that is not ready. The real
// gimbal-track is exercised by tests/integration/test_gimbald_track.py.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "track/track_process.hpp"

using gimbald::track::TrackProcess;
using gimbald::track::TrackProcessOptions;

namespace {

void run_until(boost::asio::io_context& io, const std::function<bool()>& done, double max_s) {
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(max_s));
    while (!done() && std::chrono::steady_clock::now() < deadline) {
        io.restart();
        io.run_for(std::chrono::milliseconds(5));
    }
}

// An executable shell script that sleeps: a gimbal-track that never answers.
std::string silent_program() {
    const auto path = std::filesystem::temp_directory_path() / "gimbald-test-silent-track.sh";
    std::ofstream(path) << "#!/bin/sh\nexec sleep 30\n";
    std::filesystem::permissions(path, std::filesystem::perms::owner_all);
    return path.string();
}

}  // namespace

TEST_CASE("track process: one that exits is started again, later each time", "[track]") {
    boost::asio::io_context io;
    TrackProcessOptions o;
    o.gimbal = "g";
    o.program = "/bin/true";
    o.backoff_min_s = 0.02;
    o.backoff_max_s = 0.16;
    std::vector<bool> readiness;
    TrackProcess p(io, o, {}, [&](bool ready) { readiness.push_back(ready); });
    p.start();
    const auto t0 = std::chrono::steady_clock::now();
    run_until(
        io, [&] { return p.counters().exits >= 5; }, 5);
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    p.stop();
    CHECK(p.counters().exits >= 5);
    CHECK(p.counters().starts >= p.counters().exits);
    // 0.02 + 0.04 + 0.08 + 0.16 s of backoff at least before the fifth exit.
    CHECK(took >= 0.3);
    CHECK(readiness.empty());  // never said hello
    CHECK_FALSE(p.ready());
}

TEST_CASE("track process: one that never says hello is killed and restarted", "[track]") {
    boost::asio::io_context io;
    TrackProcessOptions o;
    o.gimbal = "g";
    o.program = silent_program();
    o.hello_timeout_s = 0.1;
    o.backoff_min_s = 0.02;
    TrackProcess p(io, o, {}, {});
    p.start();
    run_until(
        io, [&] { return p.counters().starts >= 2; }, 5);
    CHECK(p.counters().exits >= 1);
    CHECK(p.counters().starts >= 2);
    const std::vector<std::uint8_t> datagram{1, 4, 0, 0, 0, 0};
    CHECK_FALSE(p.send(datagram));  // not ready: dropped, never queued
    CHECK(p.counters().dropped == 1);
    p.stop();
    CHECK_FALSE(p.pid().has_value());
}

TEST_CASE("track process: a program that cannot be started is retried", "[track]") {
    boost::asio::io_context io;
    TrackProcessOptions o;
    o.gimbal = "g";
    o.program = "/nonexistent/gimbal-track";
    o.backoff_min_s = 0.01;
    TrackProcess p(io, o, {}, {});
    p.start();
    run_until(
        io, [] { return false; }, 0.2);
    p.stop();
    CHECK(p.counters().starts == 0);
    CHECK_FALSE(p.ready());
}
