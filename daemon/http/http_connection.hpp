// One HTTP/1.1 connection: read a request (bounded header and body; the idle deadline until
// its first byte, then 10 s for the header), answer it through HttpApi, keep the connection alive
// when the client asks, hand a WebSocket upgrade of /api/stream to a WsClient and one of
// /api/video/{gimbal} to a VideoClient. Every error ends in
// fail(); a request the parser refuses gets its status (400, 413, 431) and the connection closes.
#pragma once

#include <array>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/string_body.hpp>
#include <memory>
#include <optional>
#include <string>

#include "client_slots.hpp"
#include "http_api.hpp"

namespace gimbald::http {

class HttpServer;

class HttpConnection : public std::enable_shared_from_this<HttpConnection> {
  public:
    // `slot`: this client address's share of http.max_connections_per_client.
    HttpConnection(boost::asio::ip::tcp::socket socket, HttpServer& server, std::string address,
                   ClientSlots::Slot slot);
    ~HttpConnection();

    void start();
    void close();  // daemon shutdown

  private:
    void do_read();
    void on_first_bytes(const boost::system::error_code& ec, std::size_t n);
    void read_header();
    void on_header(const boost::system::error_code& ec, std::size_t n);
    void on_read(const boost::system::error_code& ec, std::size_t n);
    void do_write(Response response);
    void on_write(const boost::system::error_code& ec, std::size_t n);
    // Sends `response` and closes, reading (and discarding) what the client still sends so
    // the close does not reset the connection before the client has read the response.
    void refuse(Response response);
    void do_drain();
    void fail(const boost::system::error_code& ec, const char* what);

    boost::beast::tcp_stream stream_;
    HttpServer& server_;
    std::string address_;  // "http:IP:PORT"
    ClientSlots::Slot slot_;
    boost::beast::flat_buffer buffer_;
    std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
    Response response_;
    bool close_after_write_ = false;
    std::array<char, 4096> drain_{};
    std::size_t drained_ = 0;
    bool closed_ = false;
};

}  // namespace gimbald::http
