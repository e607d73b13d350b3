#include "link/tcp_link.hpp"

#include <utility>

#include <boost/asio/connect.hpp>

namespace gimbald {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

StreamLinkOptions stream_options(const TcpLinkOptions& o) {
    return {.silence_timeout_s = o.silence_timeout_s,
            .queue = o.queue,
            .send_now_timeout_s = o.send_now_timeout_s};
}

Backoff backoff_from(const TcpLinkOptions& o) {
    return Backoff(BackoffOptions{.min_s = o.reconnect_min_s, .max_s = o.reconnect_max_s});
}

}  // namespace

TcpLink::TcpLink(asio::io_context& io, TcpLinkOptions options)
    : TcpLink(io, options, backoff_from(options)) {}

TcpLink::TcpLink(asio::io_context& io, TcpLinkOptions options, Backoff backoff)
    : StreamLink(io, stream_options(options), std::move(backoff)),
      options_(std::move(options)),
      resolver_(io),
      connect_timer_(io) {
    if (options_.discover()) {
        discovery_.emplace(io, DiscoveryOptions{options_.discover_address, options_.discover_port,
                                                options_.discover_reply_port,
                                                options_.discover_timeout_s, options_.discovery});
    } else {
        target_host_ = options_.host;
    }
}

std::string TcpLink::endpoint() const {
    const std::string host = target_host_.empty() ? options_.host : target_host_;
    const bool ipv6 = host.find(':') != std::string::npos;
    return (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(options_.port);
}

void TcpLink::open() {
    if (!discovery_) return connect(options_.host);
    target_host_.clear();  // re-discover: the gimbal may have a new address
    discovery_->start(guarded([this](std::optional<asio::ip::address> gimbal, std::string error) {
        if (!gimbal) return attempt_failed("discover", error);
        target_host_ = gimbal->to_string();
        connect(target_host_);
    }));
}

void TcpLink::close_attempt() {
    resolver_.cancel();
    connect_timer_.cancel();
    if (discovery_) discovery_->cancel();
}

void TcpLink::connect(const std::string& host) {
    connect_timer_.expires_after(seconds_to_duration(options_.connect_timeout_s));
    connect_timer_.async_wait(guarded([this](const boost::system::error_code& ec) {
        if (ec || connected()) return;  // the connect may have won a close race
        attempt_failed("connect", "no connection to " + endpoint() + " within " +
                                      describe_seconds(options_.connect_timeout_s));
    }));
    resolver_.async_resolve(
        host, std::to_string(options_.port),
        guarded([this](const boost::system::error_code& ec, tcp::resolver::results_type results) {
            on_resolved(ec, results);
        }));
}

void TcpLink::on_resolved(const boost::system::error_code& ec,
                          const tcp::resolver::results_type& endpoints) {
    if (ec) return attempt_failed("resolve", target_host_ + ": " + ec.message());
    stream().emplace(io());
    asio::async_connect(*stream(), endpoints,
                        guarded([this](const boost::system::error_code& connect_ec,
                                       const tcp::endpoint&) { on_connected(connect_ec); }));
}

void TcpLink::on_connected(const boost::system::error_code& ec) {
    if (ec) return attempt_failed("connect", endpoint() + ": " + ec.message());
    connect_timer_.cancel();
    boost::system::error_code ignored;
    stream()->set_option(tcp::no_delay(true), ignored);
    stream()->set_option(asio::socket_base::keep_alive(true), ignored);
    if (options_.kernel_send_buffer > 0)
        stream()->set_option(asio::socket_base::send_buffer_size(options_.kernel_send_buffer),
                             ignored);
    established();
}

}  // namespace gimbald
