// The video side of the HTTP server (contract section 18): per gimbal, one tap on its video
// (VideoTap, taken while it has viewers) that turns each access unit into one binary
// message - 8-byte big-endian timestamp in microseconds, 1 flag byte (bit 0: key frame),
// the Annex B access unit - shared by all its viewers, and the configuration text message
// {"type":"config","gimbal","codec","width","height"} read from the SPS of key frames.
// Viewers are tracked from their upgrade on (counted against http.max_connections, closed
// by stop()).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "daemon_view.hpp"
#include "logging.hpp"
#include "video/codec.hpp"
#include "video/video_tap.hpp"
#include "video_client.hpp"

namespace gimbald::http {

struct VideoFeedOptions {
    double idle_timeout_s = 30;  // WebSocket keep-alive, as for /api/stream
    double stall_s = 5;          // a write unfinished this long: the viewer is dropped
    std::size_t backlog_frames = 15;
    std::size_t send_buffer_bytes = 256 * 1024;  // SO_SNDBUF: bounds what a stalled viewer holds
};

class VideoFeeds {
  public:
    VideoFeeds(std::function<video::VideoTap*(const std::string&)> lookup, HttpStats& stats,
               VideoFeedOptions options);
    ~VideoFeeds();

    // The gimbal's video, or null (no such gimbal, or no video section).
    video::VideoTap* tap(const std::string& gimbal) const;
    // From the upgrade request on; join() once the handshake is done; leave() when gone.
    void track(VideoClient& client);
    void join(VideoClient& client);
    void leave(VideoClient& client);
    // A viewer stopped reading (dropped) or fell behind (a backlog dropped): counted, logged.
    void stalled(VideoClient& client);
    void dropped_backlog() { ++stats_.video_backlogs_dropped_total; }
    void stop();

    std::size_t clients() const { return tracked_.size(); }
    const VideoFeedOptions& options() const { return options_; }

  private:
    struct Feed {
        std::uint64_t viewer_id = 0;
        std::vector<VideoClient*> clients;
        VideoMessage config;
        std::string codec;
        int width = 0;
        int height = 0;
    };
    void on_access_unit(const std::string& gimbal, const gimbal::video::AccessUnit& au);

    std::function<video::VideoTap*(const std::string&)> lookup_;
    HttpStats& stats_;
    VideoFeedOptions options_;
    std::map<std::string, Feed> feeds_;
    std::set<VideoClient*> tracked_;
    gimbal::log::RateLimitedLog stalled_log_;
    bool stopped_ = false;
};

// The binary message of one access unit (exposed for the unit test).
std::string video_frame_message(const gimbal::video::AccessUnit& au);

}  // namespace gimbald::http
