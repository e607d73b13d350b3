// The video relay budget of contract section 17: a 1080p30 8 Mbit/s H.264 MPEG-TS with KLV
// arrives over UDP, goes through daemon/video's UdpTsInput (its worker thread demultiplexes
// and checks the KLV, contract section 14 v4) and out through two TsUdpOutputs (lib/video
// muxer) on one io_context thread, as in gimbald.
//
//   CPU      the io thread's and the input's worker thread's CPU time together against the
//            stream's duration (CLOCK_THREAD_CPUTIME_ID, /proc schedstat): target < 3 %
//   latency  per access unit, from sending the input datagram that completes it to
//            receiving the output datagram that completes it (output 1): target p99 < 5 ms
//
// The input is encoded once by ffmpeg/libx264 (CBR 8 Mbit/s, testsrc2) into the build tree
// and remuxed here with one KLV set per frame; the sender sends each frame's datagrams at
// its frame time. A benchmark, never a pass/fail timing test: it prints the figures and the
// targets, and exits non-zero only when units were lost (the smoke run's check).
//
//   bench_video_relay [--seconds 10] [--dir DIR]    (--smoke: 2 s)
#include <poll.h>
#include <pthread.h>
#include <time.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

#include "klv/local_set.hpp"
#include "logging.hpp"
#include "video/ts_demuxer.hpp"
#include "video/ts_muxer.hpp"
#include "video/udp_ts_input.hpp"
#include "video/video_output.hpp"

namespace asio = boost::asio;
namespace fs = std::filesystem;
namespace gv = gimbal::video;
namespace vd = gimbald::video;
using Clock = std::chrono::steady_clock;
using Bytes = std::vector<std::uint8_t>;

namespace {

double thread_cpu_s() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

// CPU time of this process's threads named `name` (/proc/self/task/*/comm), from schedstat
// (nanoseconds on a CPU).
double named_threads_cpu_s(const std::string& name) {
    double total = 0;
    for (const auto& task : fs::directory_iterator("/proc/self/task")) {
        std::ifstream comm(task.path() / "comm");
        std::string n;
        std::getline(comm, n);
        if (n != name) continue;
        std::ifstream stat(task.path() / "schedstat");
        unsigned long long run_ns = 0;
        stat >> run_ns;
        total += static_cast<double>(run_ns) * 1e-9;
    }
    return total;
}

Bytes read_file(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

std::uint16_t port_of(const asio::ip::udp::socket& s) {
    return s.local_endpoint().port();
}

// A valid ST 0601 local set the size of a typical one (~170 bytes): the input checks and
// decodes it as it would a camera's.
Bytes klv_set(std::size_t frame) {
    gimbal::klv::LocalSet set;
    set.add(gimbal::klv::tag_of("precision_time_stamp"),
            std::uint64_t{1'700'000'000'000'000} + frame * 33'333);
    set.add(gimbal::klv::tag_of("mission_id"), std::string("BENCH"));
    set.add(gimbal::klv::tag_of("image_source_sensor"), std::string(100, 'S'));
    set.add(gimbal::klv::tag_of("sensor_latitude"), 45.0 + static_cast<double>(frame) * 1e-6);
    set.add(gimbal::klv::tag_of("sensor_longitude"), -121.0);
    set.add(gimbal::klv::tag_of("sensor_true_altitude"), 1500.0);
    set.add(gimbal::klv::tag_of("slant_range"), 1700.0);
    set.add(gimbal::klv::tag_of("uas_datalink_ls_version_number"),
            std::uint64_t{gimbal::klv::st0601_version});
    return gimbal::klv::encode(set).value();
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const auto i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
    return v[std::min(i, v.size() - 1)];
}

}  // namespace

int main(int argc, char** argv) {
    double seconds = 10;
    fs::path dir = fs::temp_directory_path();
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--smoke") seconds = 2;
        if (a == "--seconds" && i + 1 < argc) seconds = std::max(1.0, std::atof(argv[++i]));
        if (a == "--dir" && i + 1 < argc) dir = argv[++i];
    }
    gimbal::log::configure({gimbal::log::Level::warn, gimbal::log::Format::text, {}});

    // 1. The input: encoded once per duration, then reused.
    const int duration = static_cast<int>(seconds + 0.999);
    const fs::path encoded = dir / ("video_relay_1080p30_8M_" + std::to_string(duration) + "s.ts");
    if (!fs::exists(encoded)) {
        fs::create_directories(dir);
        const std::string cmd =
            "ffmpeg -nostdin -v error -y -f lavfi -i testsrc2=size=1920x1080:rate=30 -t " +
            std::to_string(duration) +
            " -pix_fmt yuv420p -c:v libx264 -preset ultrafast -tune zerolatency -b:v 8M -minrate 8M"
            " -maxrate 8M -bufsize 2M -x264-params nal-hrd=cbr -g 30 -f mpegts " +
            encoded.string() + ".part && mv " + encoded.string() + ".part " + encoded.string();
        std::printf("encoding the input: %s\n", encoded.c_str());
        if (std::system(cmd.c_str()) != 0) {
            std::fprintf(stderr, "ffmpeg failed\n");
            return 2;
        }
    }
    std::vector<gv::AccessUnitBuffer> units;
    {
        gv::TsDemuxer d({[&](const gv::AccessUnit& au) { units.emplace_back(au); }, {}, {}});
        d.push(read_file(encoded));
        d.flush();
    }
    // 2. Remux with KLV; note which datagram completes each access unit.
    std::vector<Bytes> datagrams;
    std::vector<std::size_t> frame_first;  // first datagram of each frame's burst
    {
        gv::TsMuxer mux({}, gv::Codec::h264, [&](std::span<const std::uint8_t> c) {
            datagrams.emplace_back(c.begin(), c.end());
        });
        for (std::size_t i = 0; i < units.size(); ++i) {
            frame_first.push_back(datagrams.size());
            mux.write_klv(klv_set(i), units[i].dts ? units[i].dts : units[i].pts);
            mux.write_video(units[i].view());
        }
    }
    std::vector<std::size_t> completing;
    {
        std::size_t index = 0;
        gv::TsDemuxer d({[&](const gv::AccessUnit&) { completing.push_back(index); }, {}, {}});
        for (; index < datagrams.size(); ++index) d.push(datagrams[index]);
    }
    std::size_t total_bytes = 0;
    for (const Bytes& d : datagrams) total_bytes += d.size();
    const double input_bps =
        static_cast<double>(total_bytes) * 8.0 * 30.0 / static_cast<double>(units.size());

    // 3. Receivers for the two outputs, and the relay.
    asio::io_context rx_io;
    asio::ip::udp::socket rx1(rx_io, {asio::ip::address_v4::loopback(), 0});
    asio::ip::udp::socket rx2(rx_io, {asio::ip::address_v4::loopback(), 0});
    for (auto* s : {&rx1, &rx2}) s->set_option(asio::socket_base::receive_buffer_size(8 << 20));
    asio::ip::udp::socket probe(rx_io, {asio::ip::address_v4::loopback(), 0});
    const std::uint16_t in_port = port_of(probe);
    probe.close();

    std::vector<Clock::time_point> sent(datagrams.size());
    std::vector<Clock::time_point> received;  // per unit, output 1
    std::size_t units2 = 0;
    std::atomic<bool> stop{false};
    std::atomic<bool> relay_ready{false};
    double relay_cpu = 0, relay_wall = 0, worker_cpu = 0;
    std::size_t klv_sets = 0;
    vd::VideoInputStatus in_status;
    vd::UdpSenderStats out_stats[2];

    std::thread relay([&] {
        asio::io_context io;
        vd::VideoOutputOptions oo;
        auto url = [](const std::string& s) { return *gv::parse_video_url(s); };
        vd::TsUdpOutput out1(io, url("udp://127.0.0.1:" + std::to_string(port_of(rx1))), oo);
        vd::TsUdpOutput out2(io, url("udp://127.0.0.1:" + std::to_string(port_of(rx2))), oo);
        std::optional<std::uint64_t> klv_pts;  // the latest video DTS, as gimbald's KlvClock
        vd::UdpTsInput input(io, url("udp://127.0.0.1:" + std::to_string(in_port)), {},
                             {[&](const gv::AccessUnit& au, Clock::time_point) {
                                  klv_pts = au.dts ? au.dts : au.pts;
                                  out1.write_video(au);
                                  out2.write_video(au);
                              },
                              [&](gimbal::klv::CheckedSets& checked, Clock::time_point) {
                                  klv_sets += checked.sets.size();
                                  for (const auto& set : checked.sets) {
                                      out1.write_klv(set.bytes, klv_pts);
                                      out2.write_klv(set.bytes, klv_pts);
                                  }
                              },
                              {},
                              {}});
        input.start();
        relay_ready = true;
        const double cpu0 = thread_cpu_s();
        const double worker0 = named_threads_cpu_s("video-input");
        const auto t0 = Clock::now();
        while (!stop) io.run_for(std::chrono::milliseconds(50));
        relay_cpu = thread_cpu_s() - cpu0;
        worker_cpu = named_threads_cpu_s("video-input") - worker0;
        relay_wall = std::chrono::duration<double>(Clock::now() - t0).count();
        in_status = input.status();
        out_stats[0] = out1.stats();
        out_stats[1] = out2.stats();
        input.stop();
    });

    std::thread receiver([&] {
        gv::TsDemuxer d1(
            {[&](const gv::AccessUnit&) { received.push_back(Clock::now()); }, {}, {}});
        gv::TsDemuxer d2({[&](const gv::AccessUnit&) { ++units2; }, {}, {}});
        std::array<std::uint8_t, 65536> buf{};
        pollfd fds[2] = {{rx1.native_handle(), POLLIN, 0}, {rx2.native_handle(), POLLIN, 0}};
        rx1.non_blocking(true);
        rx2.non_blocking(true);
        while (!stop) {
            if (poll(fds, 2, 50) <= 0) continue;
            for (int k = 0; k < 2; ++k) {
                auto& s = k == 0 ? rx1 : rx2;
                for (;;) {
                    boost::system::error_code ec;
                    const std::size_t n = s.receive(asio::buffer(buf), 0, ec);
                    if (ec) break;
                    (k == 0 ? d1 : d2).push(std::span(buf.data(), n));
                }
            }
        }
    });

    // 4. Send at frame times.
    while (!relay_ready) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    {
        asio::io_context io;
        asio::ip::udp::socket tx(io, asio::ip::udp::v4());
        const asio::ip::udp::endpoint to(asio::ip::address_v4::loopback(), in_port);
        const auto start = Clock::now();
        for (std::size_t f = 0; f < frame_first.size(); ++f) {
            std::this_thread::sleep_until(start + std::chrono::microseconds(f * 1'000'000 / 30));
            const std::size_t end =
                f + 1 < frame_first.size() ? frame_first[f + 1] : datagrams.size();
            for (std::size_t i = frame_first[f]; i < end; ++i) {
                sent[i] = Clock::now();
                tx.send_to(asio::buffer(datagrams[i]), to);
            }
        }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    stop = true;
    relay.join();
    receiver.join();

    // 5. Figures.
    std::vector<double> latency_ms;
    for (std::size_t i = 0; i < std::min(received.size(), completing.size()); ++i) {
        latency_ms.push_back(
            std::chrono::duration<double, std::milli>(received[i] - sent[completing[i]]).count());
    }
    // Against the stream's duration, not the thread's lifetime: the idle time before and
    // after the stream would flatter the figure.
    const double stream_s = static_cast<double>(units.size()) / 30.0;
    const double cpu_pct = 100.0 * (relay_cpu + worker_cpu) / stream_s;
    const double p50 = percentile(latency_ms, 0.50), p99 = percentile(latency_ms, 0.99);
    const double max =
        latency_ms.empty() ? 0 : *std::max_element(latency_ms.begin(), latency_ms.end());
    std::printf(
        "video relay: 1080p30 H.264 %.1f Mbit/s (with KLV at 30 Hz), %zu units over %.1f s, "
        "UDP in -> 2 UDP outputs\n",
        input_bps / 1e6, units.size(), stream_s);
    std::printf(
        "  relay CPU: %.2f %% of a core (io thread %.3f s + input worker %.3f s for %.2f s of "
        "stream; ran %.2f s)   target < 3 %%: %s\n",
        cpu_pct, relay_cpu, worker_cpu, stream_s, relay_wall, cpu_pct < 3 ? "met" : "MISSED");
    std::printf(
        "  latency input -> output: p50 %.3f ms  p99 %.3f ms  max %.3f ms   target p99 < 5 ms: "
        "%s\n",
        p50, p99, max, p99 < 5 ? "met" : "MISSED");
    std::printf(
        "  units relayed: output 1 %zu/%zu, output 2 %zu/%zu; input cc errors %llu, "
        "datagrams sent %llu + %llu, dropped %llu + %llu\n",
        received.size(), units.size(), units2, units.size(),
        static_cast<unsigned long long>(in_status.demux.cc_errors),
        static_cast<unsigned long long>(out_stats[0].datagrams),
        static_cast<unsigned long long>(out_stats[1].datagrams),
        static_cast<unsigned long long>(out_stats[0].dropped_full + out_stats[0].dropped_error),
        static_cast<unsigned long long>(out_stats[1].dropped_full + out_stats[1].dropped_error));
    std::printf("  KLV sets checked and relayed: %zu/%zu\n", klv_sets, units.size());
    const bool complete =
        received.size() == units.size() && units2 == units.size() && klv_sets == units.size();
    if (!complete) std::fprintf(stderr, "video relay: units were lost\n");
    return complete ? 0 : 1;
}
