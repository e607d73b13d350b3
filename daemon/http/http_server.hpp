// The HTTP server of contract section 11: one acceptor on the daemon's io_context. A
// connection from outside command.allow is closed at once (counted, logged like a dropped
// datagram); so is one over http.max_connections, or over http.max_connections_per_client
// from its address (section 14). Connections and WebSocket clients are
// tracked so stop() closes them all and io_context::run() returns.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <functional>
#include <memory>
#include <set>
#include <string>

#include "client_slots.hpp"
#include "daemon_view.hpp"
#include "http_api.hpp"
#include "http_config.hpp"
#include "logging.hpp"
#include "state/event.hpp"
#include "stream_hub.hpp"
#include "video_feeds.hpp"

namespace gimbald::http {

class HttpConnection;

// The `http` section (http_config.hpp) and what the daemon derives from it or adds.
struct HttpServerOptions : gimbal::daemon::HttpConfig {
    explicit HttpServerOptions(gimbal::daemon::HttpConfig config = {})
        : HttpConfig(std::move(config)) {}
    VideoFeedOptions video;
    ApiOptions api;
    std::function<bool(const boost::asio::ip::address&)> allowed;
};

class HttpServer {
  public:
    // Binds and listens; throws boost::system::system_error when it cannot (exit code 2).
    HttpServer(boost::asio::io_context& io, HttpServerOptions options, DaemonView daemon);
    ~HttpServer();

    void start();
    void stop();

    boost::asio::ip::tcp::endpoint local_endpoint() const { return acceptor_.local_endpoint(); }
    void publish_event(const std::string& gimbal, const gimbal::state::Event& event) {
        hub_.publish_event(gimbal, event);
    }
    std::size_t websocket_clients() const { return hub_.clients(); }

    // For HttpConnection.
    HttpApi& api() { return api_; }
    StreamHub& hub() { return hub_; }
    VideoFeeds& video() { return video_; }
    HttpStats& stats() { return stats_; }
    double idle_timeout_s() const { return options_.idle_timeout_s; }
    void add(HttpConnection* c);
    void remove(HttpConnection* c);
    void count_response(unsigned status) { ++stats_.responses_total[status]; }
    // A request refused by the Host/Origin checks: a warning, rolled up.
    void count_cross_site(const std::string& source, std::string_view why);

  private:
    void do_accept();
    void on_accept(const boost::system::error_code& ec, boost::asio::ip::tcp::socket socket);
    void update_open();

    boost::asio::io_context& io_;
    HttpServerOptions options_;
    HttpStats stats_;
    HttpApi api_;
    StreamHub hub_;
    VideoFeeds video_;
    boost::asio::ip::tcp::acceptor acceptor_;
    std::set<HttpConnection*> connections_;
    ClientSlots slots_;
    gimbal::log::RateLimitedLog refused_;
    gimbal::log::RateLimitedLog over_capacity_;
    gimbal::log::RateLimitedLog cross_site_;
    bool stopped_ = false;
};

// "http:127.0.0.1:5000", "http:[::1]:5000"
std::string http_source(const boost::asio::ip::tcp::endpoint& endpoint);

}  // namespace gimbald::http
