// The JSON command socket (contract section 4): one UDP socket, one reply per accepted
// datagram, subscriptions fed with STATE and events. Requests go through the one request path
// (request_path.hpp); this class only moves datagrams and feeds its subscribers.
#pragma once

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "logging.hpp"
#include "request_path.hpp"
#include "state/event.hpp"
#include "subscriptions.hpp"

namespace gimbald {

struct CommandServerOptions {
    std::string bind = "127.0.0.1";
    std::uint16_t port = 8760;
    std::size_t max_subscribers = 64;
    std::size_t max_subscribers_per_host = 16;
    // command.allow: true when a datagram from this address may be answered.
    std::function<bool(const boost::asio::ip::address&)> allowed;
    // Signs a push to a signed subscription with its key; empty: pushes go out plain.
    std::function<std::string(const std::string& key_id, const nlohmann::json& message)> sign;
};

class CommandServer {
  public:
    using Endpoint = boost::asio::ip::udp::endpoint;

    // Binds the socket; throws boost::system::system_error when it cannot (exit code 2).
    CommandServer(boost::asio::io_context& io, CommandServerOptions options, RequestPath& path);

    void start();
    void stop();

    Endpoint local_endpoint() const { return socket_.local_endpoint(); }
    void publish_event(const std::string& gimbal, const gimbal::state::Event& event);
    std::size_t subscribers() const { return subscriptions_.size(); }
    std::uint64_t dropped_sources() const { return dropped_sources_; }

  private:
    void do_receive();
    void on_receive(const boost::system::error_code& ec, std::size_t n);
    void send(const Endpoint& to, std::string payload);
    // A datagram shared by several subscribers: sent without a copy.
    void send(const Endpoint& to, std::shared_ptr<const std::string> payload);
    void schedule_publish();
    void publish_states();
    std::string payload_for(const Endpoint& to, const nlohmann::json& message) const;

    boost::asio::io_context& io_;
    CommandServerOptions options_;
    RequestPath& path_;
    boost::asio::ip::udp::socket socket_;
    boost::asio::steady_timer publish_timer_;
    std::array<char, 65536> buffer_{};
    Endpoint sender_;
    Subscriptions subscriptions_;
    gimbal::log::RateLimitedLog dropped_;
    std::uint64_t dropped_sources_ = 0;
    bool stopped_ = false;
};

// "127.0.0.1:5000", "[::1]:5000"
std::string to_string(const boost::asio::ip::udp::endpoint& endpoint);

}  // namespace gimbald
