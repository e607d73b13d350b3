// The JSON command socket (contract section 4): one UDP socket, one reply per accepted
// datagram, subscriptions fed with STATE and events. Parsing and validation are pure
// (lib/command); this class only moves datagrams and routes requests to gimbal sessions.
#pragma once

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "command/result.hpp"
#include "gimbal_session.hpp"
#include "logging.hpp"
#include "state/event.hpp"
#include "subscriptions.hpp"

namespace gimbald {

struct CommandServerOptions {
    std::string bind = "127.0.0.1";
    std::uint16_t port = 8760;
    std::optional<std::string> token;
    std::size_t max_subscribers = 64;
    // command.allow: true when a datagram from this address may be answered.
    std::function<bool(const boost::asio::ip::address&)> allowed;
};

class CommandServer {
  public:
    using Endpoint = boost::asio::ip::udp::endpoint;

    // Binds the socket; throws boost::system::system_error when it cannot (exit code 2).
    CommandServer(boost::asio::io_context& io, CommandServerOptions options,
                  std::vector<GimbalSession*> sessions);

    void start();
    void stop();

    Endpoint local_endpoint() const { return socket_.local_endpoint(); }
    void publish_event(const std::string& gimbal, const gimbal::state::Event& event);
    std::size_t subscribers() const { return subscriptions_.size(); }

    // Handles one datagram and returns the reply; its `command` log line is written from a
    // posted handler, after the link has written what the command queued.
    nlohmann::json handle(std::string_view datagram, const Endpoint& from);

  private:
    void do_receive();
    void on_receive(const boost::system::error_code& ec, std::size_t n);
    void send(const Endpoint& to, std::string payload);
    void schedule_publish();
    void publish_states();
    double now_s() const;

    struct Routed {
        GimbalSession* session = nullptr;
        std::optional<gimbal::command::Error> error;
    };
    Routed route(const std::optional<std::string>& gimbal) const;
    nlohmann::json dispatch(const std::string& cmd, const nlohmann::json& request,
                            const std::optional<std::string>& gimbal, const Endpoint& from,
                            std::optional<gimbal::command::Error>& error,
                            std::optional<std::string>& reply_gimbal);

    boost::asio::io_context& io_;
    CommandServerOptions options_;
    std::vector<GimbalSession*> sessions_;
    boost::asio::ip::udp::socket socket_;
    boost::asio::steady_timer publish_timer_;
    std::array<char, 65536> buffer_{};
    Endpoint sender_;
    Subscriptions subscriptions_;
    std::chrono::steady_clock::time_point epoch_;
    gimbal::log::RateLimitedLog dropped_;
    bool stopped_ = false;
};

}  // namespace gimbald
