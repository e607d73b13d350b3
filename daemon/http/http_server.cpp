#include "http_server.hpp"

#include <boost/asio/socket_base.hpp>

#include "http_connection.hpp"

namespace gimbald::http {

namespace asio = boost::asio;
namespace log = gimbal::log;
using asio::ip::tcp;

void HttpServer::count_cross_site(const std::string& source, std::string_view why) {
    ++stats_.cross_site_total;
    cross_site_.poll();
    cross_site_.hit("HTTP request refused (another site's page?)",
                    {{"src", source}, {"reason", std::string(why)}});
}

std::string http_source(const tcp::endpoint& e) {
    const auto a = e.address();
    return "http:" + (a.is_v6() ? "[" + a.to_string() + "]" : a.to_string()) + ":" +
           std::to_string(e.port());
}

HttpServer::HttpServer(asio::io_context& io, HttpServerOptions options, DaemonView daemon)
    : io_(io),
      options_(std::move(options)),
      api_(daemon, options_.api, stats_),
      hub_(io, *daemon.path, stats_, options_.ws_queue_max, options_.idle_timeout_s),
      video_(daemon.video, stats_, options_.video),
      acceptor_(io),
      slots_(options_.max_connections_per_client),
      refused_(log::Level::warn, "dropped_source",
               "HTTP connections from sources not in command.allow"),
      over_capacity_(log::Level::warn, "http_over_capacity",
                     "HTTP connections refused at http.max_connections or "
                     "http.max_connections_per_client"),
      cross_site_(log::Level::warn, "http_cross_site",
                  "HTTP requests refused by the Host/Origin checks") {
    const tcp::endpoint local(options_.bind, options_.port);
    acceptor_.open(local.protocol());
    // TCP needs it to rebind at once after a restart (TIME_WAIT); a second daemon still fails.
    acceptor_.set_option(asio::socket_base::reuse_address(true));
    acceptor_.bind(local);
    acceptor_.listen(asio::socket_base::max_listen_connections);
}

HttpServer::~HttpServer() = default;

void HttpServer::start() {
    stopped_ = false;
    do_accept();
}

void HttpServer::stop() {
    stopped_ = true;
    boost::system::error_code ignored;
    acceptor_.close(ignored);
    for (auto* c : std::set<HttpConnection*>(connections_)) c->close();
    hub_.stop();
    video_.stop();
}

void HttpServer::add(HttpConnection* c) {
    connections_.insert(c);
    stats_.open_connections = connections_.size();
}

void HttpServer::remove(HttpConnection* c) {
    connections_.erase(c);
    stats_.open_connections = connections_.size();
}

void HttpServer::do_accept() {
    acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
        on_accept(ec, std::move(socket));
    });
}

void HttpServer::on_accept(const boost::system::error_code& ec, tcp::socket socket) {
    if (stopped_ || ec == asio::error::operation_aborted) return;
    if (ec) {
        // EMFILE and the like: keep accepting; the next attempt may succeed.
        log::warn("http_accept", "accept failed: " + ec.message());
        return do_accept();
    }
    boost::system::error_code peer_ec;
    const auto peer = socket.remote_endpoint(peer_ec);
    if (peer_ec) return do_accept();
    refused_.poll();
    over_capacity_.poll();
    cross_site_.poll();
    if (options_.allowed && !options_.allowed(peer.address())) {
        ++stats_.refused_total;
        refused_.hit("HTTP connection from a source not in command.allow closed",
                     {{"src", http_source(peer)}});
        socket.close(peer_ec);
        return do_accept();
    }
    if (connections_.size() + hub_.clients() + video_.clients() >= options_.max_connections) {
        ++stats_.over_capacity_total;
        over_capacity_.hit("HTTP connection closed: http.max_connections are open",
                           {{"src", http_source(peer)}, {"max", options_.max_connections}});
        socket.close(peer_ec);
        return do_accept();
    }
    auto slot = slots_.take(peer.address());
    if (!slot) {
        ++stats_.over_capacity_total;
        over_capacity_.hit(
            "HTTP connection closed: http.max_connections_per_client are open from its address",
            {{"src", http_source(peer)}, {"max_per_client", options_.max_connections_per_client}});
        socket.close(peer_ec);
        return do_accept();
    }
    ++stats_.connections_total;
    std::make_shared<HttpConnection>(std::move(socket), *this, http_source(peer), std::move(*slot))
        ->start();
    do_accept();
}

}  // namespace gimbald::http
