// gimbal-sim's running parts: the model (the protocol's, from the registry) on a 10 ms tick,
// the TCP server, the pty, discovery (for a protocol that has one), fault injection and the
// rx log, all on one io_context.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "discovery_responder.hpp"
#include "options.hpp"
#include "pty_port.hpp"
#include "rx_log.hpp"
#include "sim/device.hpp"
#include "sim/fault_injector.hpp"
#include "sim/read_faults.hpp"
#include "tcp_server.hpp"
#include "udp_port.hpp"
#include "video/sim_video_sender.hpp"

namespace gimbal_sim {

class SimApp {
  public:
    // Opens every endpoint and prints it; throws on failure (startup error).
    SimApp(boost::asio::io_context& io, const ToolOptions& options);

    void start();
    void stop();

  private:
    double now_s() const;  // seconds since start
    void arm_tick();
    void on_tick();
    // Runs the model to `now` and sends what it produced (with faults) to every listener.
    void deliver(double now);
    void on_input(const std::string& src, std::span<const std::uint8_t> bytes);
    bool stalled(double now) const;
    ReadBudget read_budget();
    void session_started();

    boost::asio::io_context& io_;
    ToolOptions options_;
    std::chrono::steady_clock::time_point epoch_;
    std::chrono::steady_clock::time_point next_tick_;
    boost::asio::steady_timer tick_timer_;
    std::unique_ptr<gimbal::sim::Device> device_;
    gimbal::sim::FaultInjector faults_;  // of the protocol's frame shape
    gimbal::sim::ReadGate read_gate_;    // how fast the gimbal reads
    std::optional<RxLog> rx_log_;
    std::optional<TcpServer> tcp_;
    std::optional<PtyPort> pty_;
    std::optional<UdpPort> udp_;
    std::optional<DiscoveryResponder> discovery_;
    std::unique_ptr<gimbald::video::SimVideoSender> video_;  // --video
    double session_start_s_ = 0;  // the latest TCP connect, or the start: faults count from it
    bool stall_reported_ = false;
    bool read_stall_reported_ = false;
    bool stopped_ = false;
};

}  // namespace gimbal_sim
