#include "video/udp_sender.hpp"

#include <stdexcept>

#include <boost/asio/ip/multicast.hpp>
#include <boost/asio/ip/unicast.hpp>

#include "logging.hpp"

namespace gimbald::video {

namespace asio = boost::asio;
using asio::ip::udp;
using SteadyClock = std::chrono::steady_clock;

namespace {

asio::ip::address parse(const std::string& text, const char* what) {
    boost::system::error_code ec;
    const auto a = asio::ip::make_address(text, ec);
    if (ec) throw std::invalid_argument(std::string(what) + " '" + text + "' is not an IP address");
    return a;
}

// Kept out of a tight loop of failing sends; also how long a send buffer gets to drain.
constexpr int send_buffer_bytes = 1024 * 1024;

}  // namespace

UdpSender::UdpSender(asio::io_context& io, const std::string& host, std::uint16_t port,
                     std::optional<int> ttl, const std::string& iface, double retry_s,
                     nlohmann::json log_fields)
    : socket_(io),
      destination_(parse(host, "output address"), port),
      ttl_(ttl),
      retry_(std::chrono::duration_cast<SteadyClock::duration>(
          std::chrono::duration<double>(retry_s))),
      log_fields_(std::move(log_fields)) {
    if (!iface.empty()) iface_ = parse(iface, "iface");
    open();
}

bool UdpSender::open() {
    boost::system::error_code ec;
    socket_.open(destination_.protocol(), ec);
    if (!ec) socket_.non_blocking(true, ec);
    if (!ec) {
        boost::system::error_code ignored;  // the kernel may cap it
        socket_.set_option(asio::socket_base::send_buffer_size(send_buffer_bytes), ignored);
    }
    const auto& addr = destination_.address();
    if (!ec && ttl_) {
        if (addr.is_multicast()) {
            socket_.set_option(asio::ip::multicast::hops(*ttl_), ec);
        } else {
            socket_.set_option(asio::ip::unicast::hops(*ttl_), ec);
        }
    }
    if (!ec && iface_ && addr.is_multicast()) {
        if (iface_->is_v4() && addr.is_v4()) {
            socket_.set_option(asio::ip::multicast::outbound_interface(iface_->to_v4()), ec);
        }
    }
    if (ec) {
        boost::system::error_code ignored;
        socket_.close(ignored);
        failed(ec);
        return false;
    }
    return true;
}

bool UdpSender::send(std::span<const std::uint8_t> datagram) {
    const auto now = SteadyClock::now();
    if (paused_until_ && now < *paused_until_) {
        ++stats_.dropped_error;
        ++dropped_since_failure_;
        return false;
    }
    paused_until_.reset();
    if (!socket_.is_open() && !open()) {
        ++stats_.dropped_error;
        ++dropped_since_failure_;
        return false;
    }
    boost::system::error_code ec;
    socket_.send_to(asio::buffer(datagram.data(), datagram.size()), destination_, 0, ec);
    if (ec == asio::error::would_block || ec == asio::error::try_again) {
        ++stats_.dropped_full;
        return false;
    }
    if (ec) {
        ++stats_.dropped_error;
        ++dropped_since_failure_;
        failed(ec);
        return false;
    }
    ++stats_.datagrams;
    stats_.bytes += datagram.size();
    if (failing_) {
        failing_ = false;
        nlohmann::json fields = log_fields_;
        fields["dropped"] = dropped_since_failure_;
        gimbal::log::info("video_output_ok", "video output sending again", fields);
        dropped_since_failure_ = 0;
    }
    return true;
}

void UdpSender::failed(const boost::system::error_code& ec) {
    ++stats_.errors;
    stats_.last_error = ec.message();
    paused_until_ = SteadyClock::now() + retry_;
    if (failing_) return;  // logged once per outage
    failing_ = true;
    nlohmann::json fields = log_fields_;
    fields["error"] = ec.message();
    gimbal::log::warn(
        "video_output_error",
        "video output cannot send: " + ec.message() + " (retrying, datagrams dropped meanwhile)",
        fields);
}

}  // namespace gimbald::video
