#include "video/sim_video_sender.hpp"

#include <time.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <boost/asio/ip/multicast.hpp>
#include <boost/asio/ip/unicast.hpp>

#include "sim_video/objects_log.hpp"
#include "video/url.hpp"

namespace gimbald::video {

namespace asio = boost::asio;
using asio::ip::udp;
using SteadyClock = std::chrono::steady_clock;

namespace {

double thread_cpu_s() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

std::uint64_t unix_us_now() {
    return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                          std::chrono::system_clock::now().time_since_epoch())
                                          .count());
}

}  // namespace

SimVideoSender::SimVideoSender(SimVideoSenderOptions options)
    : options_(std::move(options)), socket_(io_) {
    boost::system::error_code ec;
    const auto address = asio::ip::make_address(options_.host, ec);
    if (ec) throw std::runtime_error("video destination '" + options_.host + "' is not an address");
    destination_ = udp::endpoint(address, options_.port);
    socket_.open(destination_.protocol(), ec);
    if (!ec) socket_.non_blocking(true, ec);
    if (!ec && options_.ttl) {
        if (address.is_multicast())
            socket_.set_option(asio::ip::multicast::hops(*options_.ttl), ec);
        else
            socket_.set_option(asio::ip::unicast::hops(*options_.ttl), ec);
    }
    if (ec) throw std::runtime_error("video socket: " + ec.message());
    auto opened = gimbal::sim_video::SimVideoStream::open(
        options_.stream, [this](std::span<const std::uint8_t> chunk) { send(chunk); });
    if (!opened) throw std::runtime_error("video encoder: " + opened.error().message);
    stream_ = std::move(opened).value();
    if (!options_.objects_log.empty()) {
        objects_log_.open(options_.objects_log, std::ios::out | std::ios::trunc);
        if (!objects_log_)
            throw std::runtime_error("objects log '" + options_.objects_log +
                                     "': cannot be written");
    }
}

SimVideoSender::~SimVideoSender() {
    stop();
}

std::string SimVideoSender::destination() const {
    const auto a = destination_.address();
    return "udp://" + (a.is_v6() ? "[" + a.to_string() + "]" : a.to_string()) + ":" +
           std::to_string(destination_.port());
}

void SimVideoSender::start() {
    if (worker_.joinable()) return;
    {
        std::lock_guard lock(mutex_);
        stopping_ = false;
    }
    worker_ = std::thread([this] { run(); });
}

void SimVideoSender::stop() {
    if (!worker_.joinable()) return;
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

void SimVideoSender::update(const gimbal::sim::CameraView& view) {
    std::lock_guard lock(mutex_);
    view_ = view;
}

SimVideoSenderStats SimVideoSender::stats() const {
    std::lock_guard lock(mutex_);
    return stats_;
}

void SimVideoSender::send(std::span<const std::uint8_t> chunk) {
    boost::system::error_code ec;
    socket_.send_to(asio::buffer(chunk.data(), chunk.size()), destination_, 0, ec);
    std::lock_guard lock(mutex_);
    if (ec) {
        ++stats_.send_errors;
        stats_.last_error = ec.message();
        return;
    }
    ++stats_.datagrams;
    stats_.bytes += chunk.size();
}

void SimVideoSender::run() {
    const int fps = options_.stream.video.h264.fps;
    const auto period =
        std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(1.0 / fps));
    const auto started = SteadyClock::now();
    const double cpu0 = thread_cpu_s();
    auto due = started;
    std::uint64_t index = 0;
    // One second in, so the first PCR (DTS - 100 ms) is positive.
    constexpr std::int64_t pts0 = 90'000;
    for (;;) {
        std::optional<gimbal::sim::CameraView> view;
        {
            std::unique_lock lock(mutex_);
            wake_.wait_until(lock, due, [this] { return stopping_; });
            if (stopping_) break;
            view = view_;
        }
        if (view) {
            const auto pts = pts0 + static_cast<std::int64_t>(
                                        std::llround(static_cast<double>(index) * 90'000.0 / fps));
            const std::uint64_t unix_us = unix_us_now();
            const bool ok = stream_->frame(*view, unix_us, pts);
            if (ok && objects_log_.is_open()) {
                // Flushed with every frame: a test reads the truth while the video runs.
                objects_log_ << gimbal::sim_video::objects_log_lines(
                                    {index, unix_us, pts, view->model_time_s},
                                    stream_->source().objects())
                             << std::flush;
            }
            ++index;
            const auto& s = stream_->stats();
            std::lock_guard lock(mutex_);
            stats_.frames = s.frames;
            stats_.klv_sets = s.klv_sets;
            if (!ok) stats_.last_error = stream_->error();
            stats_.cpu_s = thread_cpu_s() - cpu0;
            stats_.wall_s = std::chrono::duration<double>(SteadyClock::now() - started).count();
        }
        // Fixed rate without drift; a worker that fell behind skips frames, never bursts.
        due += period;
        const auto now = SteadyClock::now();
        if (due < now) {
            const auto behind = (now - due) / period + 1;
            due += behind * period;
            std::lock_guard lock(mutex_);
            stats_.late_frames += static_cast<std::uint64_t>(behind);
        }
    }
}

std::optional<SimVideoTarget> sim_video_target(const std::string& input_url, std::string& why) {
    const auto parsed = gimbal::video::parse_video_url(input_url);
    if (!parsed) {
        why = parsed.error().message;
        return std::nullopt;
    }
    const auto& url = *parsed;
    if (url.scheme != gimbal::video::UrlScheme::udp) {
        why = "the simulated camera sends MPEG-TS over UDP; it cannot feed " + input_url;
        return std::nullopt;
    }
    SimVideoTarget t;
    t.port = url.port;
    t.ttl = url.ttl;
    boost::system::error_code ec;
    const auto address = url.host.empty() ? asio::ip::address(asio::ip::address_v4::any())
                                          : asio::ip::make_address(url.host, ec);
    if (ec) {
        why = "'" + url.host + "' is not an address";
        return std::nullopt;
    }
    if (address.is_unspecified())
        t.host = address.is_v6() ? "::1" : "127.0.0.1";
    else
        t.host = address.to_string();
    return t;
}

}  // namespace gimbald::video
