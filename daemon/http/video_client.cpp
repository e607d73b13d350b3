#include "video_client.hpp"

#include <boost/asio/socket_base.hpp>
#include <boost/beast/websocket/error.hpp>

#include "frame_policy.hpp"
#include "logging.hpp"
#include "video_feeds.hpp"

namespace gimbald::http {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace log = gimbal::log;
using SteadyClock = std::chrono::steady_clock;

namespace {

// A viewer sends nothing but control frames; a data message larger than this closes it.
constexpr std::size_t max_incoming = 4096;

}  // namespace

VideoClient::VideoClient(beast::tcp_stream&& stream, VideoFeeds& feeds, std::string gimbal,
                         std::string address, ClientSlots::Slot slot)
    : ws_(std::move(stream)),
      feeds_(feeds),
      gimbal_(std::move(gimbal)),
      address_(std::move(address)),
      slot_(std::move(slot)),
      queue_(feeds.options().backlog_frames) {}

VideoClient::~VideoClient() {
    feeds_.leave(*this);
}

void VideoClient::start(beast::http::request<beast::http::string_body> request) {
    beast::get_lowest_layer(ws_).expires_never();
    // Bounds what a viewer that stops reading holds in the kernel, so the stall shows in
    // seconds; autotuning would let it soak up megabytes first.
    boost::system::error_code ignored;
    beast::get_lowest_layer(ws_).socket().set_option(
        boost::asio::socket_base::send_buffer_size(
            static_cast<int>(feeds_.options().send_buffer_bytes)),
        ignored);
    websocket::stream_base::timeout timeout{};
    timeout.handshake_timeout = std::chrono::seconds(10);
    timeout.idle_timeout = std::chrono::duration_cast<SteadyClock::duration>(
        std::chrono::duration<double>(feeds_.options().idle_timeout_s));
    timeout.keep_alive_pings = true;
    ws_.set_option(timeout);
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& res) {
        res.set(beast::http::field::server, "gimbald/" GIMBALD_VERSION);
        add_frame_policy(res);
    }));
    ws_.read_message_max(max_incoming);
    ws_.auto_fragment(false);
    feeds_.track(*this);
    ws_.async_accept(request, [self = shared_from_this()](const boost::system::error_code& ec) {
        self->on_accept(ec);
    });
}

void VideoClient::on_accept(const boost::system::error_code& ec) {
    if (ec) return fail(ec, "handshake");
    if (closed_) return;
    joined_ = true;
    feeds_.join(*this);
    do_read();
}

void VideoClient::do_read() {
    ws_.async_read(buffer_,
                   [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                       if (ec) return self->fail(ec, "read");
                       self->buffer_.consume(self->buffer_.size());  // viewers have nothing to say
                       self->do_read();
                   });
}

void VideoClient::offer(const VideoMessage& config, const VideoMessage& frame, bool key) {
    if (closed_ || !joined_) return;
    if (queue_.writing() && SteadyClock::now() - write_started_ >
                                std::chrono::duration<double>(feeds_.options().stall_s)) {
        feeds_.stalled(*this);
        return close();
    }
    if (queue_.offer(config, frame, key) == ViewerQueue::Offer::backlog_dropped)
        feeds_.dropped_backlog();
    if (!queue_.writing()) do_write();
}

void VideoClient::do_write() {
    if (queue_.empty() || closed_) return;
    queue_.start_write();
    write_started_ = SteadyClock::now();
    ws_.text(queue_.front().text);
    ws_.async_write(boost::asio::buffer(*queue_.front().bytes),
                    [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                        self->on_write(ec);
                    });
}

void VideoClient::on_write(const boost::system::error_code& ec) {
    if (ec) {
        queue_.abort_write();
        return fail(ec, "write");
    }
    queue_.written();
    if (closed_) return;
    do_write();
}

void VideoClient::close() {
    if (closed_) return;
    closed_ = true;
    boost::system::error_code ignored;
    beast::get_lowest_layer(ws_).socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both,
                                                   ignored);
    beast::get_lowest_layer(ws_).close();
}

void VideoClient::fail(const boost::system::error_code& ec, const char* what) {
    if (ec != websocket::error::closed && ec != boost::asio::error::operation_aborted &&
        ec != boost::asio::error::eof && !closed_)
        log::debug("video_ws_error", std::string(what) + ": " + ec.message(),
                   {{"src", address_}, {"gimbal", gimbal_}});
    close();
}

}  // namespace gimbald::http
