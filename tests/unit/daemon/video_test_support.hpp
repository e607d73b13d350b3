// Helpers for the daemon/video tests: run an io_context until a condition holds, a free
// UDP port, a muxed test stream, and an RTSP server process (tests/integration/
// rtsp_server.py under Debian's /usr/bin/python3 with GStreamer's RTSP server).
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

#include "../video/ts_builder.hpp"
#include "klv/local_set.hpp"
#include "video/ts_muxer.hpp"

namespace video_test {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

inline bool run_until(boost::asio::io_context& io, const std::function<bool()>& done,
                      std::chrono::milliseconds limit = 5000ms) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done()) {
        if (std::chrono::steady_clock::now() >= deadline) return false;
        if (io.stopped()) io.restart();
        io.run_for(5ms);
    }
    return true;
}

inline void run_for(boost::asio::io_context& io, std::chrono::milliseconds duration) {
    run_until(
        io, [] { return false; }, duration);
}

inline std::uint16_t free_udp_port() {
    boost::asio::io_context io;
    boost::asio::ip::udp::socket s(io, {boost::asio::ip::address_v4::loopback(), 0});
    return s.local_endpoint().port();
}

// A valid UAS Datalink set (checksum right) whose time stamp and latitude follow `i`.
inline Bytes klv_set(int i) {
    gimbal::klv::LocalSet set;
    set.add(gimbal::klv::tag_of("precision_time_stamp"),
            std::uint64_t{1'700'000'000'000'000} + static_cast<std::uint64_t>(i) * 33'333);
    set.add(gimbal::klv::tag_of("sensor_latitude"), 45.0 + i * 1e-4);
    set.add(gimbal::klv::tag_of("uas_datalink_ls_version_number"),
            std::uint64_t{gimbal::klv::st0601_version});
    return gimbal::klv::encode(set).value();
}

// `count` access units (key frame every 10, 640x360 SPS) at 30 fps with a KLV set after
// each, as the datagrams a TsMuxer produces.
struct TestStream {
    std::vector<gimbal::video::AccessUnitBuffer> units;
    std::vector<Bytes> klv;
    std::vector<Bytes> datagrams;

    explicit TestStream(int count, std::size_t slice = 3000) {
        gimbal::video::TsMuxer mux({}, gimbal::video::Codec::h264,
                                   [this](std::span<const std::uint8_t> c) {
                                       datagrams.emplace_back(c.begin(), c.end());
                                   });
        for (int i = 0; i < count; ++i) {
            gimbal::video::AccessUnitBuffer au;
            au.key_frame = i % 10 == 0;
            au.data = gimbal::test::h264_au(au.key_frame, slice, static_cast<std::uint8_t>(i));
            au.pts = 90000 + static_cast<std::uint64_t>(i) * 3000;
            mux.write_video(au.view());
            klv.push_back(klv_set(i));
            mux.write_klv(klv.back(), au.pts);
            units.push_back(std::move(au));
        }
    }
};

// The RTSP test server as a child process; killed when this goes away.
class RtspServer {
  public:
    explicit RtspServer(const std::vector<std::string>& extra = {}) {
        const std::string script =
            std::string(GIMBAL_SOURCE_DIR) + "/tests/integration/rtsp_server.py";
        int fds[2];
        if (pipe(fds) != 0) return;
        pid_ = fork();
        if (pid_ == 0) {
            dup2(fds[1], STDOUT_FILENO);
            close(fds[0]);
            close(fds[1]);
            std::vector<std::string> args = {"/usr/bin/python3", script, "--port", "0"};
            args.insert(args.end(), extra.begin(), extra.end());
            std::vector<char*> argv;
            for (auto& a : args) argv.push_back(a.data());
            argv.push_back(nullptr);
            execv(argv[0], argv.data());
            _exit(127);
        }
        close(fds[1]);
        out_ = fdopen(fds[0], "r");
        char line[256] = {};
        if (out_ && fgets(line, sizeof line, out_)) {
            unsigned port = 0;
            if (std::sscanf(line, "ready %u", &port) == 1) port_ = static_cast<std::uint16_t>(port);
        }
    }
    ~RtspServer() { kill_now(); }
    RtspServer(const RtspServer&) = delete;
    RtspServer& operator=(const RtspServer&) = delete;

    std::uint16_t port() const { return port_; }
    void kill_now() {
        if (pid_ > 0) {
            ::kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
            pid_ = -1;
        }
        if (out_) {
            fclose(out_);
            out_ = nullptr;
        }
    }

  private:
    pid_t pid_ = -1;
    FILE* out_ = nullptr;
    std::uint16_t port_ = 0;
};

}  // namespace video_test
