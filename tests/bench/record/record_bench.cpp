// Recording throughput: what the flight recorder costs gimbald at a given packet rate.
//
// Runs the daemon's own recording path - the Orion inbound splitter (a second framer over
// the received bytes) and the Recorder (buffer + writer thread + pcapng files) - on an
// io_context, fed like a TCP link: every millisecond a chunk of `rate/1000` whole
// GeolocateTelemetry-sized Orion frames. Reports the process CPU time (io thread + writer
// thread, from getrusage) as a percentage of one core, with and without recording, so the
// difference is the recorder's cost.
//
//   bench_record [--rate 10000] [--seconds 60] [--dir /tmp] [--max-file-mb 100]
#include <sys/resource.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "logging.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "record/recorder.hpp"
#include "record/recording_link.hpp"

namespace {

double cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const auto s = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) / 1e6; };
    return s(usage.ru_utime) + s(usage.ru_stime);
}

struct Result {
    double cpu_percent = 0;
    std::uint64_t packets = 0;
    std::uint64_t dropped = 0;
    std::uint64_t bytes = 0;
};

// Feeds `rate` frames per second for `seconds`; records them when `recorder` is set.
Result run(int rate, double seconds, gimbald::record::Recorder* recorder) {
    boost::asio::io_context io;
    std::unique_ptr<gimbald::record::InboundSplitter> splitter;
    if (recorder) splitter = gimbald::record::make_inbound_splitter("orion", *recorder, 0);
    // One millisecond of traffic: rate/1000 frames of a 68-byte payload (GeolocateTelemetry).
    std::vector<std::uint8_t> chunk;
    const int per_tick = rate / 1000;
    for (int i = 0; i < per_tick; ++i) {
        std::vector<std::uint8_t> payload(68, static_cast<std::uint8_t>(i));
        gimbal::orion::append_frame(0xD1, payload, chunk);
    }
    volatile std::uint64_t sink = 0;  // without recording: touch the bytes like a reader would
    boost::asio::steady_timer timer(io);
    const auto start = std::chrono::steady_clock::now();
    auto next = start;
    std::uint64_t packets = 0;
    const double cpu_before = cpu_seconds();
    std::function<void()> tick = [&] {
        if (splitter)
            splitter->push(chunk);
        else
            for (auto b : chunk) sink = sink + b;
        packets += static_cast<std::uint64_t>(per_tick);
        next += std::chrono::milliseconds(1);
        if (next - start >= std::chrono::duration<double>(seconds)) return;
        timer.expires_at(next);
        timer.async_wait([&](const boost::system::error_code&) { tick(); });
    };
    tick();
    io.run();
    Result r;
    r.packets = packets;
    if (recorder) {
        recorder->stop();  // the last chunk's write and fdatasync belong to the cost
        r.dropped = recorder->dropped();
        r.bytes = recorder->snapshot()["bytes"].get<std::uint64_t>();
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.cpu_percent = 100.0 * (cpu_seconds() - cpu_before) / wall;
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    int rate = 10000;
    double seconds = 60;
    std::string dir = std::filesystem::temp_directory_path().string();
    double max_file_mb = 100;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i];
        if (key == "--rate")
            rate = std::atoi(argv[i + 1]);
        else if (key == "--seconds")
            seconds = std::atof(argv[i + 1]);
        else if (key == "--dir")
            dir = argv[i + 1];
        else if (key == "--max-file-mb")
            max_file_mb = std::atof(argv[i + 1]);
        else {
            std::fprintf(stderr, "unknown option %s\n", argv[i]);
            return 1;
        }
    }
    gimbal::log::Settings settings;
    settings.level = gimbal::log::Level::warn;
    gimbal::log::configure(settings);

    const Result base = run(rate, seconds, nullptr);
    std::printf("without recording: %.2f %% of a core (%llu packets)\n", base.cpu_percent,
                static_cast<unsigned long long>(base.packets));

    const auto rec_dir = std::filesystem::path(dir) / "gimbald-record-bench";
    std::filesystem::remove_all(rec_dir);
    std::filesystem::create_directories(rec_dir);
    boost::asio::io_context recorder_io;  // the report timer's; not run (logs only)
    gimbald::record::RecorderOptions options;
    options.dir = rec_dir.string();
    options.max_file_mb = max_file_mb;
    options.max_total_mb = 100000;
    options.interfaces = {{"gimbal:bench", "orion bench"}, {"json", "json"}};
    gimbald::record::Recorder recorder(recorder_io, options);
    const Result rec = run(rate, seconds, &recorder);
    std::printf(
        "with recording:    %.2f %% of a core (%llu packets, %llu dropped, %.1f MB "
        "in the last file)\n",
        rec.cpu_percent, static_cast<unsigned long long>(rec.packets),
        static_cast<unsigned long long>(rec.dropped), double(rec.bytes) / 1e6);
    const double cost = rec.cpu_percent - base.cpu_percent;
    std::printf("recorder cost:     %.2f %% of a core at %d packets/s (target < 5 %%: %s)\n", cost,
                rate, cost < 5 ? "met" : "MISSED");
    std::filesystem::remove_all(rec_dir);
    return 0;
}
