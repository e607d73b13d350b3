#include "http_connection.hpp"

#include <algorithm>
#include <boost/asio/write.hpp>
#include <boost/beast/core/string.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/write.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <charconv>
#include <chrono>

#include "command/envelope.hpp"
#include "frame_policy.hpp"
#include "http_server.hpp"
#include "logging.hpp"
#include "static_files.hpp"
#include "video_client.hpp"
#include "ws_client.hpp"

namespace gimbald::http {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace log = gimbal::log;
using beast::http::status;

namespace {

// Contract section 11 limits: a request's header, and its body (the datagram limit).
constexpr std::uint32_t header_limit = 8192;
constexpr std::uint64_t body_limit = gimbal::command::max_datagram;
// Contract section 14: once a request has begun, its header must be complete within this
// (slowloris); before its first byte only the idle timeout applies (keep-alive).
constexpr double header_time_s = 10.0;
// After a refusal: how much more of the client's request is read and thrown away, and for
// how long, before the connection closes.
constexpr std::size_t drain_limit = 65536;
constexpr auto drain_time = std::chrono::seconds(2);

std::chrono::steady_clock::duration idle(double seconds) {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(seconds));
}

std::optional<std::size_t> declared_length(beast::string_view text) {
    std::size_t n = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return n;
}

bool is_http_error(const boost::system::error_code& ec) {
    return ec.category() == beast::http::make_error_code(beast::http::error::bad_target).category();
}

}  // namespace

HttpConnection::HttpConnection(asio::ip::tcp::socket socket, HttpServer& server,
                               std::string address, ClientSlots::Slot slot)
    : stream_(std::move(socket)),
      server_(server),
      address_(std::move(address)),
      slot_(std::move(slot)) {
    server_.add(this);
}

HttpConnection::~HttpConnection() {
    server_.remove(this);
}

void HttpConnection::start() {
    do_read();
}

void HttpConnection::close() {
    if (closed_) return;
    closed_ = true;
    stream_.close();
}

void HttpConnection::do_read() {
    parser_.emplace();
    parser_->header_limit(header_limit);
    parser_->body_limit(body_limit);
    if (buffer_.size() > 0) return read_header();  // pipelined: the next request has begun
    // Waiting for a request (a kept-alive connection between requests): the idle timeout.
    stream_.expires_after(idle(server_.idle_timeout_s()));
    stream_.async_read_some(
        buffer_.prepare(header_limit),
        [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
            self->on_first_bytes(ec, n);
        });
}

void HttpConnection::on_first_bytes(const boost::system::error_code& ec, std::size_t n) {
    if (closed_) return;
    if (ec == asio::error::eof) return on_read(beast::http::error::end_of_stream, 0);
    if (ec) return fail(ec, "read");
    buffer_.commit(n);
    read_header();
}

void HttpConnection::read_header() {
    // One deadline for the header from its first byte, then one for the body: a client that
    // trickles bytes cannot hold the connection longer than that.
    stream_.expires_after(idle(std::min(header_time_s, server_.idle_timeout_s())));
    beast::http::async_read_header(
        stream_, buffer_, *parser_,
        [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
            self->on_header(ec, n);
        });
}

void HttpConnection::on_header(const boost::system::error_code& ec, std::size_t n) {
    if (ec || closed_ || parser_->is_done()) return on_read(ec, n);
    auto read_body = [self = shared_from_this()] {
        self->stream_.expires_after(idle(self->server_.idle_timeout_s()));
        beast::http::async_read(
            self->stream_, self->buffer_, *self->parser_,
            [self](const boost::system::error_code& e, std::size_t m) { self->on_read(e, m); });
    };
    // curl and others wait a second for this before they send a body over 1 KiB.
    const auto expect = parser_->get()[beast::http::field::expect];
    if (beast::iequals(expect, "100-continue")) {
        static const std::string go_on = "HTTP/1.1 100 Continue\r\n\r\n";
        asio::async_write(stream_, asio::buffer(go_on),
                          [self = shared_from_this(), read_body](const boost::system::error_code& e,
                                                                 std::size_t) {
                              if (e) return self->fail(e, "write");
                              read_body();
                          });
        return;
    }
    read_body();
}

void HttpConnection::on_read(const boost::system::error_code& ec, std::size_t) {
    if (closed_) return;
    if (ec == beast::http::error::end_of_stream) {
        // The client closed between requests: close our side too.
        boost::system::error_code ignored;
        stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
        return close();
    }
    const unsigned version = parser_->get().version() ? parser_->get().version() : 11;
    if (ec == beast::http::error::header_limit)
        return refuse(HttpApi::error(status::request_header_fields_too_large, version,
                                     "request header larger than 8192 bytes"));
    if (ec == beast::http::error::body_limit) {
        // A command over the limit is answered by the request path, unread (too_large).
        const auto& header = parser_->get();
        if (target_path(std::string(header.target())) == "/api/command" &&
            !server_.api().cross_site_problem(header)) {
            // Beast stops at a Content-Length over the limit before it calls the header
            // done: the field is read as text.
            return refuse(server_.api().too_large(
                version, address_, declared_length(header[beast::http::field::content_length])));
        }
        return refuse(HttpApi::error(status::payload_too_large, version,
                                     "request body larger than 8192 bytes"));
    }
    if (ec && is_http_error(ec) && ec != beast::http::error::partial_message)
        return refuse(HttpApi::error(status::bad_request, version,
                                     "malformed HTTP request: " + ec.message()));
    if (ec) return fail(ec, "read");

    auto request = parser_->release();
    if (auto problem = server_.api().cross_site_problem(request)) {
        server_.count_cross_site(address_, *problem);
        return refuse(HttpApi::error(status::forbidden, version, *problem));
    }
    const std::string target(request.target());
    if (target_path(target) == "/api/stream" && beast::websocket::is_upgrade(request)) {
        // The stream continues as a WebSocket; this connection object ends here.
        stream_.expires_never();
        std::make_shared<WsClient>(std::move(stream_), server_.hub(), address_, std::move(slot_))
            ->start(std::move(request));
        closed_ = true;
        return;
    }
    if (const auto gimbal = video_gimbal(target_path(target));
        gimbal && beast::websocket::is_upgrade(request) && server_.video().tap(*gimbal)) {
        // Contract section 18: the gimbal's video; an unknown gimbal or one without video
        // is answered 404 by HttpApi below.
        stream_.expires_never();
        std::make_shared<VideoClient>(std::move(stream_), server_.video(), *gimbal, address_,
                                      std::move(slot_))
            ->start(std::move(request));
        closed_ = true;
        return;
    }
    auto response = server_.api().handle(request, address_);
    response.keep_alive(request.keep_alive());
    response.prepare_payload();
    if (request.method() == beast::http::verb::head) response.body().clear();
    do_write(std::move(response));
}

void HttpConnection::do_write(Response response) {
    server_.count_response(response.result_int());
    response_ = std::move(response);
    add_frame_policy(response_.base());
    close_after_write_ = close_after_write_ || response_.need_eof();
    stream_.expires_after(idle(server_.idle_timeout_s()));
    beast::http::async_write(stream_, response_,
                             [self = shared_from_this()](const boost::system::error_code& ec,
                                                         std::size_t n) { self->on_write(ec, n); });
}

void HttpConnection::on_write(const boost::system::error_code& ec, std::size_t) {
    if (closed_) return;
    if (ec) return fail(ec, "write");
    if (close_after_write_) {
        boost::system::error_code ignored;
        stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
        // Read what the client may still send until it closes, then close.
        drained_ = 0;
        stream_.expires_after(drain_time);
        return do_drain();
    }
    do_read();
}

void HttpConnection::refuse(Response response) {
    log::debug("http_refused", response.body(), {{"src", address_}});
    response.keep_alive(false);
    response.prepare_payload();
    close_after_write_ = true;
    do_write(std::move(response));
}

void HttpConnection::do_drain() {
    stream_.async_read_some(
        asio::buffer(drain_),
        [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
            self->drained_ += n;
            if (ec || self->closed_ || self->drained_ > drain_limit) return self->close();
            self->do_drain();
        });
}

void HttpConnection::fail(const boost::system::error_code& ec, const char* what) {
    if (ec != asio::error::operation_aborted && ec != beast::error::timeout &&
        ec != asio::error::eof && ec != asio::error::connection_reset &&
        ec != beast::http::error::partial_message)
        log::debug("http_error", std::string(what) + ": " + ec.message(), {{"src", address_}});
    close();
}

}  // namespace gimbald::http
