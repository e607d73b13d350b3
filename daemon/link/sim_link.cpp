#include "link/sim_link.hpp"

#include <stdexcept>
#include <utility>

#include <boost/asio/post.hpp>

#include "link/seconds.hpp"

namespace gimbald {

SimLink::SimLink(boost::asio::io_context& io, std::unique_ptr<gimbal::sim::Device> device,
                 SimLinkOptions options)
    : io_(io),
      device_(std::move(device)),
      tick_(seconds_to_duration(options.tick_s)),
      epoch_(std::chrono::steady_clock::now()),
      timer_(io) {
    if (!device_) throw std::invalid_argument("SimLink needs a device");
    if (tick_ <= std::chrono::steady_clock::duration::zero()) {
        throw std::invalid_argument("SimLink tick must be positive");
    }
}

void SimLink::start(DataHandler on_data, StateHandler on_state, ErrorHandler on_error) {
    stop();
    on_data_ = std::move(on_data);
    on_state_ = std::move(on_state);
    on_error_ = std::move(on_error);
    connected_ = true;
    next_tick_ = std::chrono::steady_clock::now() + tick_;
    arm_tick();
    // Like the other links, the connect is reported from the io_context, not from start().
    boost::asio::post(io_, lifetime_.wrap([this] {
        if (on_state_) on_state_(true);
    }));
}

void SimLink::stop() {
    lifetime_.reset();
    timer_.cancel();
    connected_ = false;
    on_data_ = nullptr;
    on_state_ = nullptr;
    on_error_ = nullptr;
}

bool SimLink::send(std::vector<std::uint8_t> packet) {
    if (!connected_) {
        ++stats_.tx_dropped;
        return false;
    }
    send_now(packet);
    return true;
}

bool SimLink::send_safety(std::vector<std::uint8_t> packet, WrittenHandler on_written) {
    if (!connected_) return false;
    send_now(packet);
    if (on_written)
        boost::asio::post(io_, lifetime_.wrap([h = std::move(on_written)] { h(true); }));
    return true;
}

bool SimLink::send_now(std::span<const std::uint8_t> packet) {
    if (!connected_) return false;
    if (packet.empty()) return true;
    device_->receive(packet, now_s());
    stats_.tx_bytes += packet.size();
    ++stats_.tx_packets;
    return true;
}

double SimLink::now_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
}

void SimLink::arm_tick() {
    timer_.expires_at(next_tick_);
    timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (!ec) on_tick();
    }));
}

void SimLink::on_tick() {
    produced_.clear();
    device_->advance(now_s(), produced_);
    if (advance_listener_) advance_listener_(*device_);
    if (!produced_.empty()) {
        stats_.rx_bytes += produced_.size();
        stats_.last_rx = std::chrono::steady_clock::now();
        const std::uint64_t generation = lifetime_.generation();
        if (on_data_) on_data_(produced_);
        if (generation != lifetime_.generation()) return;  // stopped from the handler
    }
    // Fixed rate without drift; after a stall (debugger, overloaded host) skip, do not burst.
    next_tick_ += tick_;
    const auto now = std::chrono::steady_clock::now();
    if (next_tick_ < now) next_tick_ = now + tick_;
    arm_tick();
}

}  // namespace gimbald
