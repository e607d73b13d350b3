// gimbal-replay's running parts: the recorded chunks on a steady-clock schedule, sent to the
// TCP server and/or pty borrowed from gimbal-sim, with progress lines, all on one io_context.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "options.hpp"
#include "pty_port.hpp"
#include "record/gimbal_stream.hpp"
#include "tcp_server.hpp"

namespace gimbal_replay {

class ReplayApp {
  public:
    // Opens every endpoint and prints it; throws on failure (startup error).
    ReplayApp(boost::asio::io_context& io, const ReplayOptions& options,
              gimbal::record::GimbalStream stream);

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
    double recorded_s(std::size_t index) const;

    boost::asio::io_context& io_;
    ReplayOptions options_;
    gimbal::record::GimbalStream stream_;
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
