#include "ws_client.hpp"

#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/version.hpp>
#include <boost/beast/websocket/error.hpp>
#include <chrono>

#include "command/envelope.hpp"
#include "frame_policy.hpp"
#include "logging.hpp"
#include "stream_hub.hpp"

namespace gimbald::http {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace log = gimbal::log;

WsClient::WsClient(beast::tcp_stream&& stream, StreamHub& hub, std::string address,
                   ClientSlots::Slot slot)
    : ws_(std::move(stream)), hub_(hub), address_(std::move(address)), slot_(std::move(slot)) {}

WsClient::~WsClient() {
    hub_.remove(*this);
}

void WsClient::start(beast::http::request<beast::http::string_body> request) {
    // The HTTP connection's deadline no longer applies: the stream's own timeouts do. A
    // client that answers no ping within the idle timeout is closed.
    beast::get_lowest_layer(ws_).expires_never();
    websocket::stream_base::timeout timeout{};
    timeout.handshake_timeout = std::chrono::seconds(10);
    timeout.idle_timeout = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(hub_.idle_timeout_s()));
    timeout.keep_alive_pings = true;
    ws_.set_option(timeout);
    // Also decorates the handshake's refusals (Beast answers a bad upgrade itself).
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& res) {
        res.set(beast::http::field::server, "gimbald/" GIMBALD_VERSION);
        add_frame_policy(res);
    }));
    // A request has the datagram limit here too, enforced by do_read() as the message
    // arrives: Beast's own limit would close with 1009 before the too_large reply.
    ws_.read_message_max(0);
    ws_.text(true);
    // One frame per message: a STATE is one write, not a train of 4 KiB fragments.
    ws_.auto_fragment(false);
    hub_.track(*this);  // from now on: counted against max_connections, closed on stop
    ws_.async_accept(request, [self = shared_from_this()](const boost::system::error_code& ec) {
        self->on_accept(ec);
    });
}

void WsClient::on_accept(const boost::system::error_code& ec) {
    if (ec) return fail(ec, "handshake");
    hub_.add(*this);
    do_read();
}

void WsClient::do_read() {
    // At most one byte past the limit is kept: that byte says the message is over it.
    const std::size_t room = gimbal::command::max_request_bytes + 1 - buffer_.size();
    ws_.async_read_some(buffer_, room,
                        [self = shared_from_this()](const boost::system::error_code& ec,
                                                    std::size_t n) { self->on_read(ec, n); });
}

void WsClient::on_read(const boost::system::error_code& ec, std::size_t) {
    // Protocol errors: Beast has already sent close 1002.
    if (ec) return fail(ec, "read");
    if (closed_) return;
    if (!ws_.got_text()) {
        buffer_.consume(buffer_.size());
        return close_with(websocket::close_code::unknown_data, "binary messages are not accepted");
    }
    if (buffer_.size() > gimbal::command::max_request_bytes) {
        // Answered unread, like an oversize datagram; the rest of it is not read but
        // discarded by the closing handshake.
        buffer_.consume(buffer_.size());
        if (auto reply = hub_.too_large(*this))
            send(std::make_shared<const std::string>(std::move(*reply)));
        return close_with(
            websocket::close_code::too_big,
            "message larger than " + std::to_string(gimbal::command::max_request_bytes) + " bytes");
    }
    if (!ws_.is_message_done()) return do_read();
    const std::string text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    auto answer = hub_.on_message(*this, text);
    if (answer.close) return close_with(*answer.close, answer.reason);
    if (answer.reply) send(std::make_shared<const std::string>(std::move(*answer.reply)));
    do_read();
}

void WsClient::send(std::shared_ptr<const std::string> text) {
    if (closed_ || closing_) return;
    if (queue_.size() >= hub_.queue_max()) {
        hub_.dropped(*this, queue_.size());
        close();
        return;
    }
    queue_.push_back(std::move(text));
    if (!writing_) do_write();
}

void WsClient::do_write() {
    if (queue_.empty() || closed_) return;
    writing_ = true;
    ws_.async_write(boost::asio::buffer(*queue_.front()),
                    [self = shared_from_this()](const boost::system::error_code& ec,
                                                std::size_t n) { self->on_write(ec, n); });
}

void WsClient::on_write(const boost::system::error_code& ec, std::size_t) {
    writing_ = false;
    if (ec) return fail(ec, "write");
    if (closed_) return;  // dropped after this write had finished
    queue_.pop_front();
    if (pending_close_) {
        // A close frame may not overlap a write: it goes out once the write is done.
        auto reason = std::move(*pending_close_);
        pending_close_.reset();
        queue_.clear();
        writing_ = true;
        ws_.async_close(reason, [self = shared_from_this()](const boost::system::error_code&) {
            self->writing_ = false;
        });
        return;
    }
    do_write();
}

void WsClient::close_with(websocket::close_code code, std::string reason) {
    log::info("websocket_close", "closing a WebSocket client: " + reason,
              {{"src", address_}, {"code", static_cast<int>(code)}});
    websocket::close_reason why(code, reason);
    closing_ = true;
    if (writing_) {
        pending_close_ = std::move(why);
        return;
    }
    queue_.clear();
    writing_ = true;
    ws_.async_close(why, [self = shared_from_this()](const boost::system::error_code&) {
        self->writing_ = false;
    });
    // The read loop stops here; the peer's close reply ends the connection.
}

void WsClient::close() {
    if (closed_) return;
    closed_ = true;
    // The queue stays: a write in flight still reads its front; it goes with this object.
    boost::system::error_code ignored;
    beast::get_lowest_layer(ws_).socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both,
                                                   ignored);
    beast::get_lowest_layer(ws_).close();
}

void WsClient::fail(const boost::system::error_code& ec, const char* what) {
    if (ec == websocket::error::closed || ec == boost::asio::error::operation_aborted ||
        ec == boost::asio::error::eof || closed_) {
        close();
        return;
    }
    // A message that could not be sent is counted and logged (contract section 14, v4).
    if (std::string_view(what) == "write")
        hub_.send_failed(*this, queue_.empty() ? 0 : queue_.front()->size(), ec);
    else
        log::debug("websocket_error", std::string(what) + ": " + ec.message(), {{"src", address_}});
    close();
}

}  // namespace gimbald::http
