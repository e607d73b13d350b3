// MPEG-TS over UDP: binds the port (to the group address for multicast, joined on `iface`
// or the default interface), takes only the datagrams of its source (SourcePin: the
// configured `video.source`, else the first sender, pinned) and hands each to its TsWorker,
// which demultiplexes it and checks the KLV on a thread of its own; the access units and
// KLV sets come back here, on the io thread. It watches for silence: no datagram for
// timeout_s is "disconnected" (video_down); the first datagram after is "connected"
// (video_up). A multicast input that stays silent leaves and rejoins the group with backoff
// (a switch that lost our IGMP membership); a socket error closes it and reopens with
// backoff.
#pragma once

#include <array>
#include <optional>

#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>

#include "link/lifetime.hpp"
#include "logging.hpp"
#include "video/source_pin.hpp"
#include "video/ts_worker.hpp"
#include "video/video_input.hpp"

namespace gimbald::video {

class UdpTsInput final : public VideoInput {
  public:
    UdpTsInput(boost::asio::io_context& io, gimbal::video::VideoUrl url, VideoInputOptions options,
               VideoInputHandlers handlers);
    ~UdpTsInput() override;

    void start() override;
    void stop() override;
    VideoInputStatus status() const override;

    bool multicast() const { return group_.has_value(); }
    // The bound port (useful with port 0... not allowed by the URL, so for logs and tests).
    std::uint16_t local_port() const;

  private:
    void open();
    void close();
    void retry_later(const std::string& error);
    void receive();
    void on_datagram(std::size_t n);
    void on_batch(TsBatch& batch);
    void tick();
    void set_connected(bool connected);

    gimbal::video::VideoUrl url_;
    VideoInputOptions options_;
    VideoInputHandlers handlers_;
    boost::asio::ip::udp::endpoint bind_;
    std::optional<boost::asio::ip::address> group_;
    std::optional<boost::asio::ip::address> iface_;
    boost::asio::ip::udp::socket socket_;
    boost::asio::steady_timer retry_timer_;
    boost::asio::steady_timer tick_timer_;
    Backoff backoff_;
    Lifetime lifetime_;
    boost::asio::io_context& io_;
    std::unique_ptr<TsWorker> worker_;  // while running
    TsWorkerCounters worker_counters_;  // the last worker's, kept over a stop
    SourcePin source_;
    gimbal::log::RateLimitedLog foreign_log_;
    gimbal::video::StreamInfoTracker info_;
    std::array<std::uint8_t, 65536> buffer_{};
    boost::asio::ip::udp::endpoint sender_;
    Clock::time_point last_data_{};
    Clock::time_point opened_at_{};
    bool running_ = false;
    bool connected_ = false;
    std::uint64_t rejoins_ = 0;
    std::string last_error_;      // the latest failure, for STATE
    std::string reported_error_;  // logged already; cleared once data flows
    Clock::time_point epoch_ = Clock::now();
};

}  // namespace gimbald::video
