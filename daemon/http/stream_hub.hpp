// GET /api/stream (contract section 11): every WebSocket client gets STATE per gimbal at its
// rate (2 Hz until it subscribes otherwise) and every event, in the datagram format of
// section 4.1. One snapshot and one JSON dump per gimbal per tick are shared by every client
// due then. Client messages: subscribe/unsubscribe act on the stream; every other request
// goes through the one request path, like POST /api/command.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "daemon_view.hpp"
#include "logging.hpp"
#include "request_path.hpp"
#include "state/event.hpp"

namespace gimbald::http {

class WsClient;

class StreamHub {
  public:
    StreamHub(boost::asio::io_context& io, RequestPath& path, HttpStats& stats,
              std::size_t queue_max, double idle_timeout_s);

    // A client from its upgrade request on (counted, closed by stop()); add() when its
    // handshake is done and the stream starts; remove() when it is gone.
    void track(WsClient& client);
    void add(WsClient& client);
    void remove(WsClient& client);
    void publish_event(const std::string& gimbal, const gimbal::state::Event& event);
    // A client's queue overflowed: counted and logged; the client closes itself.
    void dropped(WsClient& client, std::size_t queued);
    // A message to a client could not be written: counted and logged (rolled up); the
    // client closes itself.
    void send_failed(WsClient& client, std::size_t bytes, const boost::system::error_code& ec);
    void stop();  // closes every client

    struct Answer {
        std::optional<std::string> reply;  // text to send back
        std::optional<boost::beast::websocket::close_code> close;
        std::string reason;
    };
    Answer on_message(WsClient& client, std::string_view text);
    // A message over the request limit, not read to its end: the too_large reply, if any.
    std::optional<std::string> too_large(WsClient& client);

    std::size_t queue_max() const { return queue_max_; }
    double idle_timeout_s() const { return idle_timeout_s_; }
    std::size_t clients() const { return clients_.size(); }  // handshakes included

  private:
    void count_open();
    std::string subscribe(WsClient& client, const nlohmann::json& request, bool unsubscribe);
    void schedule();
    void tick();

    RequestPath& path_;
    HttpStats& stats_;
    std::size_t queue_max_;
    double idle_timeout_s_;
    boost::asio::steady_timer timer_;
    std::vector<WsClient*> clients_;
    gimbal::log::RateLimitedLog send_failed_;
    bool stopped_ = false;
};

}  // namespace gimbald::http
