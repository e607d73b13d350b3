#include "sim_app.hpp"

#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace gimbal_sim {

namespace asio = boost::asio;

namespace {

gimbal::sim::FaultOptions fault_options(const ToolOptions& o) {
    gimbal::sim::FaultOptions f;
    f.corrupt_fraction = o.corrupt_fraction;
    f.junk_every = o.junk_every;
    f.seed = o.scenario.seed;
    return f;
}

gimbal::sim::ReadFaultOptions read_fault_options(const ToolOptions& o) {
    return {.stall_after_s = o.stall_reading_after_s,
            .stall_for_s = o.stall_reading_for_s,
            .baud = o.read_baud};
}

// A small receive buffer makes a gimbal that reads slowly push back on the sender at once.
constexpr int slow_reader_receive_buffer = 4096;

void note(const std::string& text) {
    std::cerr << "gimbal-sim: " << text << std::endl;
}

}  // namespace

SimApp::SimApp(asio::io_context& io, const ToolOptions& options)
    : io_(io),
      options_(options),
      epoch_(std::chrono::steady_clock::now()),
      tick_timer_(io),
      device_(options.entry().simulator.make(options.scenario)),
      faults_(fault_options(options), options.entry().simulator.fault_frames()),
      read_gate_(read_fault_options(options)) {
    if (!options_.rx_log.empty()) rx_log_.emplace(options_.rx_log, options_.entry());

    if (options_.tcp) {
        tcp_.emplace(
            io, options_.bind, options_.port,
            [this](std::span<const std::uint8_t> b) { on_input("tcp", b); },
            [this](bool connected, const std::string& peer) {
                if (connected) {
                    session_start_s_ = now_s();
                    stall_reported_ = false;
                    session_started();
                } else if (rx_log_) {
                    rx_log_->reset("tcp");
                }
                note(std::string(connected ? "client connected: " : "client gone: ") + peer);
            },
            read_gate_.active() ? std::optional<int>(slow_reader_receive_buffer) : std::nullopt);
        if (read_gate_.active()) tcp_->set_read_policy([this] { return read_budget(); });
        const auto endpoint = tcp_->local_endpoint();
        std::cout << "tcp: " << endpoint.address().to_string() << ":" << endpoint.port()
                  << std::endl;
    }
    if (options_.pty) {
        pty_.emplace(
            io, options_.pty_link, [this](std::span<const std::uint8_t> b) { on_input("pty", b); },
            [this](bool open) {
                if (open) session_started();
                if (!open && rx_log_) rx_log_->reset("pty");
                note(open ? "pty opened" : "pty closed");
            });
        if (read_gate_.active()) pty_->set_read_policy([this] { return read_budget(); });
        std::cout << "pty: " << pty_->device() << std::endl;
    }
    if (options_.udp_port) {
        udp_.emplace(io, options_.bind, *options_.udp_port,
                     [this](std::span<const std::uint8_t> b) { on_input("udp", b); });
        const auto endpoint = udp_->local_endpoint();
        std::cout << "udp: " << endpoint.address().to_string() << ":" << endpoint.port()
                  << std::endl;
    }
    if (!options_.video.url.empty()) {
        std::string error;
        auto video = video_sender_options(options_.video, options_.entry(), error);
        if (!video) throw std::runtime_error(error);
        video_ = std::make_unique<gimbald::video::SimVideoSender>(std::move(*video));
        std::cout << "video: " << video_->destination() << std::endl;
    }
    if (options_.discovery) {
        const auto& simulator = options_.entry().simulator;
        try {
            discovery_.emplace(io, options_.discovery_port, options_.discovery_reply_port,
                               simulator.is_discovery_request, simulator.discovery_reply());
            std::cout << "discovery: 0.0.0.0:" << discovery_->port() << std::endl;
        } catch (const std::exception& e) {
            // Another simulator may hold the port; serving without discovery beats not at all.
            note("discovery off: udp port " + std::to_string(options_.discovery_port) + ": " +
                 e.what());
        }
    }
}

double SimApp::now_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
}

void SimApp::start() {
    if (tcp_) tcp_->start();
    if (pty_) pty_->start();
    if (udp_) udp_->start();
    if (discovery_) discovery_->start();
    if (video_) video_->start();
    next_tick_ = std::chrono::steady_clock::now();
    on_tick();
}

void SimApp::stop() {
    stopped_ = true;
    tick_timer_.cancel();
    if (tcp_) tcp_->stop();
    if (pty_) pty_->stop();
    if (udp_) udp_->stop();
    if (discovery_) discovery_->stop();
    if (video_) {
        video_->stop();
        const auto s = video_->stats();
        char cpu[96];
        std::snprintf(cpu, sizeof cpu, "%.2f s CPU in %.1f s (%.1f %% of a core)", s.cpu_s,
                      s.wall_s, s.wall_s > 0 ? 100.0 * s.cpu_s / s.wall_s : 0.0);
        note("video: " + std::to_string(s.frames) + " frames, " + std::to_string(s.klv_sets) +
             " KLV sets, " + std::to_string(s.bytes) + " bytes, " + std::to_string(s.late_frames) +
             " frames skipped, " + std::to_string(s.send_errors) + " send errors; render+encode " +
             cpu);
    }
}

void SimApp::arm_tick() {
    // Absolute deadlines: the tick does not drift when a handler runs late.
    next_tick_ += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(options_.tick_s));
    const auto now = std::chrono::steady_clock::now();
    if (next_tick_ < now) next_tick_ = now;  // after a stop (SIGSTOP, debugger): no burst
    tick_timer_.expires_at(next_tick_);
    tick_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (!ec && !stopped_) on_tick();
    });
}

void SimApp::session_started() {
    read_gate_.session_start(now_s());
    read_stall_reported_ = false;
}

ReadBudget SimApp::read_budget() {
    const auto budget = read_gate_.budget(now_s());
    return {budget.bytes, budget.retry_after_s};
}

bool SimApp::stalled(double now) const {
    if (options_.stall_for_s <= 0) return false;
    const double since = now - session_start_s_;
    return since >= options_.stall_after_s && since < options_.stall_after_s + options_.stall_for_s;
}

void SimApp::on_tick() {
    const double now = now_s();
    if (tcp_ && tcp_->has_client() && options_.drop_after_s > 0 &&
        now - session_start_s_ >= options_.drop_after_s) {
        note("dropping the client (--drop-after)");
        tcp_->drop_client();
    }

    if (stalled(now) && !stall_reported_) {
        note("stalling (--stall-after)");
        stall_reported_ = true;
    }
    if (read_gate_.stalled(now) != read_stall_reported_) {
        read_stall_reported_ = !read_stall_reported_;
        note(read_stall_reported_ ? "not reading (--stall-reading-after)" : "reading again");
    }
    deliver(now);
    arm_tick();
}

void SimApp::deliver(double now) {
    std::vector<std::uint8_t> out;
    device_->advance(now, out);
    if (video_)  // the camera as the model just left it (SimVideoSender copies it)
        if (const auto view = options_.entry().simulator.camera(*device_)) video_->update(*view);
    if (out.empty() || stalled(now)) return;  // a stalled gimbal says nothing; the model runs on
    std::vector<std::uint8_t> wire;
    if (faults_.active()) {
        faults_.apply(out, wire);
    } else {
        wire.swap(out);
    }
    if (tcp_) tcp_->write(wire);
    if (pty_) pty_->write(wire);
    if (udp_) udp_->write(wire);
}

void SimApp::on_input(const std::string& src, std::span<const std::uint8_t> bytes) {
    const double now = now_s();
    read_gate_.consumed(bytes.size(), now);
    if (rx_log_) rx_log_->received(src, bytes, now);
    device_->receive(bytes, now);
    deliver(now);  // answers (command echoes, requested packets) go out now, not next tick
}

}  // namespace gimbal_sim
