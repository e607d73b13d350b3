// RTSP input (H.264/H.265 over RTP, TCP or UDP transport) through FFmpeg's libavformat.
//
// Why a thread: libavformat's RTSP client is blocking (avformat_open_input, av_read_frame);
// it cannot run on the daemon's io_context without stalling every gimbal link. So each
// RTSP input owns one thread that connects, reads and reconnects with backoff (0.5 s
// doubling to 10 s, with jitter); an interrupt callback makes every blocking call return when
// stop() is asked for (joined within about a second) or when no data came for timeout_s.
// The thread never touches daemon state: each access unit is copied (with SPS/PPS inserted
// before key frames when the camera gives them only in the SDP) and posted to the
// io_context, where the handlers run; at most max_queued_units (and max_queued_bytes
// together) wait there, later ones are dropped and counted, as is a unit over
// max_access_unit_bytes.
//
// A hostile camera (contract section 14 v4): libavformat's allocations are capped (one
// allocation at most 9 MiB, av_max_alloc - a 2 GB Content-Length is refused, an endless
// fragmented frame stops growing), its RTP reordering queue is short, and the interrupt
// callback watches redirects. libavformat follows an RTSP redirect by itself and would keep
// sending the input's credentials to the new host; the callback sees the new URL before any
// byte goes to it, stops a redirect to another host:port, and this input follows it without
// the credentials (logged: rtsp_redirect). A redirect loop ends after max_redirects. Every
// failure is shown in STATE (`last_error`, `reconnects`) and logged, rolled up.
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "logging.hpp"
#include "video/video_input.hpp"

namespace gimbald::video {

class RtspInput final : public VideoInput {
  public:
    RtspInput(boost::asio::io_context& io, gimbal::video::VideoUrl url, VideoInputOptions options,
              VideoInputHandlers handlers);
    ~RtspInput() override;

    void start() override;
    void stop() override;
    VideoInputStatus status() const override;

  private:
    struct Shared;  // what the thread and the io side both see
    struct Attempt;

    void run(std::shared_ptr<Shared> shared);
    bool read_session(Shared& shared);
    void open_and_read(Shared& shared, Attempt& attempt);
    void read_frames(Shared& shared, void* format, Attempt& attempt);
    void post_connected(bool connected, std::string error);
    void post_redirect(std::string from, std::string to);

    boost::asio::io_context& io_;
    gimbal::video::VideoUrl url_;
    VideoInputOptions options_;
    VideoInputHandlers handlers_;
    std::shared_ptr<Shared> shared_;
    std::shared_ptr<const char> alive_;  // posted handlers run only while it lives
    std::thread thread_;
    // io side
    bool connected_ = false;
    std::string last_error_;
    gimbal::video::StreamInfoTracker info_;
    gimbal::log::RateLimitedLog failure_log_;
    gimbal::log::RateLimitedLog redirect_log_;
    Clock::time_point epoch_ = Clock::now();
};

}  // namespace gimbald::video
