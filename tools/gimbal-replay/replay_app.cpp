#include "replay_app.hpp"

#include <cstdio>
#include <iostream>

#include "video/url.hpp"

namespace gimbal_replay {

namespace asio = boost::asio;

namespace {

std::string fixed(double value, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return buf;
}

}  // namespace

ReplayApp::ReplayApp(asio::io_context& io, const ReplayOptions& options,
                     gimbal::record::GimbalStream stream, gimbal::record::VideoStream video)
    : io_(io),
      options_(options),
      stream_(std::move(stream)),
      video_(std::move(video)),
      video_timer_(io),
      send_timer_(io),
      progress_timer_(io) {
    // Only the TS as received goes out; gimbald makes its generated KLV again from the flight.
    std::erase_if(video_.chunks, [](const auto& c) { return c.generated; });
    if (!stream_.chunks.empty()) origin_us_ = stream_.chunks.front().time_us;
    if (!video_.chunks.empty() &&
        (stream_.chunks.empty() || video_.chunks.front().time_us < origin_us_))
        origin_us_ = video_.chunks.front().time_us;
    if (!options_.video.empty()) {
        const auto url = gimbal::video::parse_video_url(options_.video);
        video_to_ = asio::ip::udp::endpoint(asio::ip::make_address(url->host), url->port);
        video_socket_.emplace(io_, video_to_.protocol());
        video_socket_->non_blocking(true);
        std::cout << "video: " << options_.video << std::endl;
    }
    const auto on_rx = [this](std::span<const std::uint8_t> bytes) {
        ignored_rx_bytes_ += bytes.size();
    };
    if (options_.tcp) {
        tcp_.emplace(io_, options_.bind, options_.port, on_rx,
                     [this](bool connected, const std::string& peer) {
                         on_controller(connected, "tcp client " + peer);
                     });
        const auto ep = tcp_->local_endpoint();
        std::cout << "tcp: " << ep.address().to_string() << ":" << ep.port() << std::endl;
    }
    if (options_.pty) {
        pty_.emplace(io_, options_.pty_link, on_rx,
                     [this](bool open) { on_controller(open, "pty"); });
        std::cout << "pty: " << pty_->device() << std::endl;
    }
}

void ReplayApp::start() {
    if (tcp_) tcp_->start();
    if (pty_) pty_->start();
}

void ReplayApp::stop() {
    if (stopped_) return;
    stopped_ = true;
    send_timer_.cancel();
    video_timer_.cancel();
    progress_timer_.cancel();
    if (tcp_) tcp_->stop();
    if (pty_) pty_->stop();
    if (on_stop_) on_stop_();
}

void ReplayApp::on_controller(bool connected, const std::string& who) {
    std::cerr << "gimbal-replay: " << who << (connected ? " connected" : " went away") << std::endl;
    if (connected && !playing_ && !stopped_ && rounds_ == 0 && next_ == 0) begin_playback();
}

double ReplayApp::recorded_s(std::size_t index) const {
    if (stream_.chunks.empty()) return 0;
    const auto& chunks = stream_.chunks;
    return static_cast<double>(chunks[std::min(index, chunks.size() - 1)].time_us -
                               chunks.front().time_us) *
           1e-6;
}

// Gimbal bytes and video share one clock: recorded time since the first of either.
ReplayApp::Clock::time_point ReplayApp::due_at(std::int64_t time_us) const {
    const double wall_s = static_cast<double>(time_us - origin_us_) * 1e-6 / options_.speed;
    return started_at_ + std::chrono::duration_cast<Clock::duration>(
                             std::chrono::duration<double>(std::max(0.0, wall_s)));
}

ReplayApp::Clock::time_point ReplayApp::due_time(std::size_t index) const {
    return due_at(stream_.chunks[std::min(index, stream_.chunks.size() - 1)].time_us);
}

bool ReplayApp::video_done() const {
    return !video_socket_ || next_video_ >= video_.chunks.size();
}

void ReplayApp::send_video_due() {
    if (stopped_ || !video_socket_) return;
    const auto now = Clock::now();
    while (next_video_ < video_.chunks.size() &&
           due_at(video_.chunks[next_video_].time_us) <= now) {
        const auto& bytes = video_.chunks[next_video_].bytes;
        boost::system::error_code ec;
        video_socket_->send_to(asio::buffer(bytes), video_to_, 0, ec);
        ++(ec ? video_errors_ : video_datagrams_);
        ++next_video_;
    }
    if (video_done()) {
        if (next_ >= stream_.chunks.size()) finish();
        return;
    }
    video_timer_.expires_at(due_at(video_.chunks[next_video_].time_us));
    video_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) send_video_due();
    });
}

void ReplayApp::begin_playback() {
    playing_ = true;
    started_at_ = Clock::now();
    std::cout << "playing: gimbal " << stream_.gimbal.name << " ("
              << (stream_.gimbal.protocol.empty() ? "unknown protocol" : stream_.gimbal.protocol)
              << "), " << stream_.chunks.size() << " packets, "
              << fixed(recorded_s(stream_.chunks.size()), 1) << " s recorded, speed "
              << options_.speed << std::endl;
    if (video_socket_)
        std::cout << "playing: video of gimbal " << video_.gimbal << ", " << video_.chunks.size()
                  << " datagrams" << std::endl;
    arm_progress();
    send_video_due();
    send_due();
}

void ReplayApp::send_due() {
    if (stopped_) return;
    const auto now = Clock::now();
    const auto& chunks = stream_.chunks;
    while (next_ < chunks.size() && due_time(next_) <= now) {
        const auto& bytes = chunks[next_].bytes;
        if (tcp_) tcp_->write(bytes);
        if (pty_) pty_->write(bytes);
        ++sent_packets_;
        sent_bytes_ += bytes.size();
        ++next_;
    }
    if (next_ >= chunks.size()) {
        if (video_done()) finish();
        return;
    }
    send_timer_.expires_at(due_time(next_));
    send_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) send_due();
    });
}

void ReplayApp::finish() {
    const double wall_s = std::chrono::duration<double>(Clock::now() - started_at_).count();
    std::cout << "done: " << sent_packets_ << " packets, " << sent_bytes_ << " bytes, "
              << fixed(recorded_s(stream_.chunks.size()), 1) << " s recorded in "
              << fixed(wall_s, 1) << " s";
    if (video_socket_)
        std::cout << "; video: " << video_datagrams_ << " datagrams"
                  << (video_errors_ ? " (" + std::to_string(video_errors_) + " not sent)" : "");
    std::cout << std::endl;
    if (options_.loop && (!stream_.chunks.empty() || !video_.chunks.empty())) {
        ++rounds_;
        next_ = 0;
        next_video_ = 0;
        video_datagrams_ = 0;
        video_errors_ = 0;
        sent_packets_ = 0;
        sent_bytes_ = 0;
        started_at_ = Clock::now();
        std::cerr << "gimbal-replay: loop " << rounds_ + 1 << std::endl;
        send_video_due();
        send_due();
        return;
    }
    playing_ = false;
    progress_timer_.cancel();
    if (options_.hold) return;  // endpoints stay open until a signal
    wait_drained(100);
}

// Lets the TCP client read what is still queued (up to 5 s), then stops: run() returns.
void ReplayApp::wait_drained(int tries_left) {
    if (stopped_) return;
    if (tries_left <= 0 || !tcp_ || tcp_->queued_bytes() == 0) {
        // A last moment for the kernel to hand the final bytes over before the close.
        send_timer_.expires_after(std::chrono::milliseconds(200));
        send_timer_.async_wait([this](const boost::system::error_code& ec) {
            if (!ec) stop();
        });
        return;
    }
    send_timer_.expires_after(std::chrono::milliseconds(50));
    send_timer_.async_wait([this, tries_left](const boost::system::error_code& ec) {
        if (!ec) wait_drained(tries_left - 1);
    });
}

void ReplayApp::arm_progress() {
    if (options_.progress_every_s <= 0) return;
    progress_timer_.expires_after(std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(options_.progress_every_s)));
    progress_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || !playing_) return;
        const double total = recorded_s(stream_.chunks.size());
        const double at = next_ == 0 ? 0.0 : recorded_s(next_ - 1);
        std::cerr << "gimbal-replay: " << fixed(at, 1) << " / " << fixed(total, 1)
                  << " s recorded (" << fixed(total > 0 ? 100.0 * at / total : 100.0, 0) << " %), "
                  << sent_packets_ << " packets, " << sent_bytes_ << " bytes"
                  << (ignored_rx_bytes_ ? ", " + std::to_string(ignored_rx_bytes_) +
                                              " bytes from the controller ignored"
                                        : std::string())
                  << std::endl;
        arm_progress();
    });
}

}  // namespace gimbal_replay
