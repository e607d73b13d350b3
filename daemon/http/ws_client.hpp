// One WebSocket client of GET /api/stream: the handshake, a read loop that hands each text
// message to the StreamHub (a message over the request limit is answered too_large and the
// stream closed with 1009, having read no more of it than the limit), and a bounded send
// queue. A client whose queue is full is not
// reading: it is dropped (logged) so it cannot hold memory or slow anyone else.
#pragma once

#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/websocket/stream.hpp>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "client_slots.hpp"
#include "state/state_push.hpp"

namespace gimbald::http {

class StreamHub;

// What a client asked for with {"cmd":"subscribe",...}; on connect: every gimbal at 2 Hz.
struct StreamSubscription {
    bool open = false;                  // the handshake is done: the stream runs
    std::optional<std::string> gimbal;  // nullopt: every gimbal
    double rate_hz = 2.0;
    bool events = true;
    bool state = true;                    // false after unsubscribe
    gimbal::state::StreamOptions stream;  // keys, changes, full_every_s
    // With stream.changes: what this client last got of each gimbal (a subscribe starts
    // afresh: its first push is a full STATE).
    std::map<std::string, gimbal::state::DeltaCursor> cursors;
    double next_state_s = 0;  // steady seconds
};

class WsClient : public std::enable_shared_from_this<WsClient> {
  public:
    // `slot`: the HTTP connection's share of http.max_connections_per_client, kept.
    WsClient(boost::beast::tcp_stream&& stream, StreamHub& hub, std::string address,
             ClientSlots::Slot slot);
    ~WsClient();

    // Completes the handshake of the upgrade request read by the HTTP connection.
    void start(boost::beast::http::request<boost::beast::http::string_body> request);
    // Queues one text message. A full queue drops the client.
    void send(std::shared_ptr<const std::string> text);
    // Closes the socket at once (daemon shutdown, dropped client).
    void close();

    const std::string& address() const { return address_; }
    StreamSubscription& subscription() { return subscription_; }

  private:
    void on_accept(const boost::system::error_code& ec);
    void do_read();
    void on_read(const boost::system::error_code& ec, std::size_t n);
    void do_write();
    void on_write(const boost::system::error_code& ec, std::size_t n);
    void close_with(boost::beast::websocket::close_code code, std::string reason);
    void fail(const boost::system::error_code& ec, const char* what);

    boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
    StreamHub& hub_;
    std::string address_;
    ClientSlots::Slot slot_;
    boost::beast::flat_buffer buffer_;
    std::deque<std::shared_ptr<const std::string>> queue_;
    StreamSubscription subscription_;
    std::optional<boost::beast::websocket::close_reason> pending_close_;
    bool writing_ = false;
    bool closing_ = false;  // a close frame is on its way
    bool closed_ = false;
};

}  // namespace gimbald::http
