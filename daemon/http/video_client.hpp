// One viewer of GET /api/video/{gimbal} (contract section 18, format in docs/http.md): the
// WebSocket handshake, a read loop that only serves control frames (anything the viewer
// sends is ignored), and its ViewerQueue of whole messages - the configuration (text) and
// one binary message per access unit. Falling behind costs the viewer, never the others: a
// backlog is dropped up to the next key frame (ViewerQueue); a write that has not finished
// for VideoFeedOptions::stall_s means the viewer stopped reading: it is dropped.
#pragma once

#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/websocket/stream.hpp>
#include <chrono>
#include <memory>
#include <string>

#include "client_slots.hpp"
#include "viewer_queue.hpp"

namespace gimbald::http {

class VideoFeeds;

class VideoClient : public std::enable_shared_from_this<VideoClient> {
  public:
    VideoClient(boost::beast::tcp_stream&& stream, VideoFeeds& feeds, std::string gimbal,
                std::string address, ClientSlots::Slot slot);
    ~VideoClient();

    void start(boost::beast::http::request<boost::beast::http::string_body> request);
    // One access unit for this viewer. `config` is the current configuration message (sent
    // before the first key frame and again when it changes).
    void offer(const VideoMessage& config, const VideoMessage& frame, bool key);
    void close();  // at once (daemon shutdown, dropped viewer)

    const std::string& gimbal() const { return gimbal_; }
    const std::string& address() const { return address_; }

  private:
    void on_accept(const boost::system::error_code& ec);
    void do_read();
    void do_write();
    void on_write(const boost::system::error_code& ec);
    void fail(const boost::system::error_code& ec, const char* what);

    boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
    VideoFeeds& feeds_;
    std::string gimbal_;
    std::string address_;
    ClientSlots::Slot slot_;
    boost::beast::flat_buffer buffer_;
    ViewerQueue queue_;
    std::chrono::steady_clock::time_point write_started_{};
    bool joined_ = false;
    bool closed_ = false;
};

}  // namespace gimbald::http
