// The JSON command socket (contract section 4): one UDP socket, one reply per accepted
// datagram, subscriptions fed with STATE and events. Requests go through the one request path
// (request_path.hpp); this class only moves datagrams and feeds its subscribers.
#pragma once

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <functional>
#include <map>
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

// The largest UDP payload over IPv4 (65,535 - 20 - 8): a reply or push over it cannot be sent.
inline constexpr std::size_t max_datagram_bytes = 65507;

// What the socket could not deliver (STATE `command`, contract section 14 v4).
struct SendCounters {
    std::uint64_t failed = 0;            // replies and pushes the socket refused
    std::uint64_t pushes_too_large = 0;  // pushes over one datagram, replaced by a notice
};

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
    const SendCounters& send_counters() const { return sent_; }

  private:
    enum class Kind { reply, push };
    // Notices already made this tick, per message: shared by its plain subscribers.
    using Notices = std::map<const void*, std::shared_ptr<const std::string>>;

    void do_receive();
    void on_receive(const boost::system::error_code& ec, std::size_t n);
    // A datagram shared by several subscribers is sent without a copy. A send that fails is
    // logged (rolled up) and counted.
    void send(const Endpoint& to, std::shared_ptr<const std::string> payload, Kind kind);
    void send_failed(const Endpoint& to, Kind kind, std::size_t bytes,
                     const boost::system::error_code& ec);
    // A push to `to`: sent as it is when it fits one datagram, else replaced by a too_large
    // event naming its size and largest keys (docs/json-api.md), logged and counted.
    // `carried` gives what the push carries (a STATE, a patch, an event), for the notice.
    // Returns false when the push was replaced.
    bool push(const Endpoint& to, std::shared_ptr<const std::string> payload,
              const std::string& gimbal, const std::function<nlohmann::json()>& carried,
              Notices& notices);
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
    gimbal::log::RateLimitedLog send_failed_;
    gimbal::log::RateLimitedLog too_large_;
    std::uint64_t dropped_sources_ = 0;
    SendCounters sent_;
    bool stopped_ = false;
};

// "127.0.0.1:5000", "[::1]:5000"
std::string to_string(const boost::asio::ip::udp::endpoint& endpoint);

}  // namespace gimbald
