// In-process simulated gimbal: a gimbal::sim::Device driven by a 10 ms steady_timer. What the
// device produces arrives through the DataHandler like bytes from a real link; every send
// hands its bytes straight to the device (there is no queue). Always connected after start().
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "link/lifetime.hpp"
#include "link/link.hpp"
#include "sim/device.hpp"

namespace gimbald {

struct SimLinkOptions {
    double tick_s = 0.01;
};

class SimLink final : public Link {
  public:
    SimLink(boost::asio::io_context& io, std::unique_ptr<gimbal::sim::Device> device,
            SimLinkOptions options = {});

    void start(DataHandler on_data, StateHandler on_state, ErrorHandler on_error) override;
    void stop() override;
    bool connected() const override { return connected_; }
    bool send(std::vector<std::uint8_t> packet) override;
    bool send_kept(std::vector<std::uint8_t> packet) override { return send(std::move(packet)); }
    // No queue to jump: the device takes the packet at once; `on_written` follows from the
    // io_context like on the other links.
    bool send_safety(std::vector<std::uint8_t> packet, WrittenHandler on_written) override;
    bool send_now(std::span<const std::uint8_t> packet) override;
    const LinkStats& stats() const override { return stats_; }
    std::string type() const override { return "sim"; }
    std::string endpoint() const override { return "sim"; }
    // Called on every tick right after the model advanced (the simulated video takes the
    // camera's view there).
    void set_advance_listener(std::function<void(const gimbal::sim::Device&)> listener) {
        advance_listener_ = std::move(listener);
    }

  private:
    double now_s() const;  // device time: seconds since this link was made (monotonic)
    void arm_tick();
    void on_tick();

    boost::asio::io_context& io_;
    std::unique_ptr<gimbal::sim::Device> device_;
    std::chrono::steady_clock::duration tick_;
    std::chrono::steady_clock::time_point epoch_;
    std::chrono::steady_clock::time_point next_tick_{};
    boost::asio::steady_timer timer_;
    Lifetime lifetime_;
    DataHandler on_data_;
    StateHandler on_state_;
    ErrorHandler on_error_;
    bool connected_ = false;
    LinkStats stats_;
    std::vector<std::uint8_t> produced_;
    std::function<void(const gimbal::sim::Device&)> advance_listener_;
};

}  // namespace gimbald
