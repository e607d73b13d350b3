// gimbal-replay's running parts: the recorded chunks on a steady-clock schedule, sent to the
// TCP server and/or pty borrowed from gimbal-sim, and the recorded video's datagrams to a UDP
// address on the same clock, with progress lines, all on one io_context.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "options.hpp"
#include "pty_port.hpp"
#include "record/gimbal_stream.hpp"
#include "record/video_stream.hpp"
#include "tcp_server.hpp"

namespace gimbal_replay {

class ReplayApp {
  public:
    // Opens every endpoint and prints it; throws on failure (startup error).
    // `video`: the gimbal's recorded video, sent to options.video (empty: none).
    ReplayApp(boost::asio::io_context& io, const ReplayOptions& options,
              gimbal::record::GimbalStream stream, gimbal::record::VideoStream video = {});

    void start();
    void stop();
    // Called once by stop(): main() cancels its signal wait there so run() can return.
    void on_stop(std::function<void()> f) { on_stop_ = std::move(f); }

  private:
    using Clock = std::chrono::steady_clock;
    void on_controller(bool connected, const std::string& who);
    void begin_playback();
    void schedule();
    void send_due();
    void finish();
    void wait_drained(int tries_left);
    void arm_progress();
    Clock::time_point due_time(std::size_t index) const;
    Clock::time_point due_at(std::int64_t time_us) const;
    double recorded_s(std::size_t index) const;
    void send_video_due();
    bool video_done() const;

    boost::asio::io_context& io_;
    ReplayOptions options_;
    gimbal::record::GimbalStream stream_;
    gimbal::record::VideoStream video_;
    std::int64_t origin_us_ = 0;  // the first recorded time of either stream
    std::optional<boost::asio::ip::udp::socket> video_socket_;
    boost::asio::ip::udp::endpoint video_to_;
    boost::asio::steady_timer video_timer_;
    std::size_t next_video_ = 0;
    std::uint64_t video_datagrams_ = 0;
    std::uint64_t video_errors_ = 0;
    std::optional<gimbal_sim::TcpServer> tcp_;
    std::optional<gimbal_sim::PtyPort> pty_;
    boost::asio::steady_timer send_timer_;
    boost::asio::steady_timer progress_timer_;
    Clock::time_point started_at_;
    std::size_t next_ = 0;
    bool playing_ = false;
    std::function<void()> on_stop_;
    bool stopped_ = false;
    unsigned rounds_ = 0;
    std::uint64_t sent_packets_ = 0;
    std::uint64_t sent_bytes_ = 0;
    std::uint64_t ignored_rx_bytes_ = 0;
};

}  // namespace gimbal_replay
