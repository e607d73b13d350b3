// RTSP input (H.264/H.265 over RTP, TCP or UDP transport) through FFmpeg's libavformat.
//
// Why a thread: libavformat's RTSP client is blocking (avformat_open_input, av_read_frame);
// it cannot run on the daemon's io_context without stalling every gimbal link. So each
// RTSP input owns one thread that connects, reads and reconnects with backoff; an
// interrupt callback makes every blocking call return when stop() is asked for (joined
// within about a second) or when no data came for timeout_s. The thread never touches
// daemon state: each access unit is copied (with SPS/PPS inserted before key frames when
// the camera gives them only in the SDP) and posted to the io_context, where the handlers
// run; at most max_queued_units wait there, later ones are dropped and counted.
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

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
    struct Session;

    void run(std::shared_ptr<Shared> shared);
    bool read_session(Shared& shared);
    void post_connected(bool connected, std::string error);

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
    Clock::time_point epoch_ = Clock::now();
};

}  // namespace gimbald::video
