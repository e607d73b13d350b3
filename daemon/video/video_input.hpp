// A gimbal's video input (contract section 17): MPEG-TS over UDP (unicast or multicast) or
// RTSP. Both deliver access units (Annex B, with SPS/PPS before key frames) and KLV units
// on the daemon's io_context, report connected/disconnected (data within a timeout), and
// reconnect or rejoin with backoff. Nothing is decoded.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>

#include <boost/asio/io_context.hpp>

#include "link/backoff.hpp"
#include "video/codec.hpp"
#include "video/stream_info.hpp"
#include "video/ts_demuxer.hpp"
#include "video/url.hpp"

namespace gimbald::video {

using Clock = std::chrono::steady_clock;

struct VideoInputOptions {
    double timeout_s = 2.0;  // no data this long: disconnected (the URL's timeout_s wins)
    BackoffOptions backoff{0.5, 10.0, 0.2};
    // RTSP: access units handed to the io_context and not yet handled; more are dropped.
    std::size_t max_queued_units = 64;
    nlohmann::json log_fields = nlohmann::json::object();  // added to every log line
};

struct VideoInputStatus {
    std::string input;  // the URL as configured
    bool connected = false;
    gimbal::video::StreamInfo stream;               // codec, size, fps, bit rate, counts
    std::optional<gimbal::video::KlvCarriage> klv;  // the stream carries KLV (TS inputs)
    gimbal::video::DemuxStats demux;                // TS inputs: CC errors, junk, drops...
    std::uint64_t klv_units = 0;
    std::uint64_t reconnects = 0;     // attempts after the first (RTSP) or rejoins (multicast)
    std::uint64_t dropped_units = 0;  // RTSP: the io_context fell behind
    std::string last_error;
};

struct VideoInputHandlers {
    std::function<void(const gimbal::video::AccessUnit&, Clock::time_point arrival)> access_unit;
    std::function<void(const gimbal::video::KlvUnit&, Clock::time_point arrival)> klv;
    std::function<void(bool connected)> connection;  // after video_up / video_down is logged
    // UDP inputs: every datagram as received (the recorder's "video" interface).
    std::function<void(std::span<const std::uint8_t> ts, Clock::time_point arrival)> ts_bytes;
};

class VideoInput {
  public:
    virtual ~VideoInput() = default;
    virtual void start() = 0;
    // Closes everything; no handler runs after stop() returns. RTSP: joins its thread
    // within about a second.
    virtual void stop() = 0;
    virtual VideoInputStatus status() const = 0;
};

// udp:// -> UdpTsInput, rtsp:// -> RtspInput. Throws std::invalid_argument for klv-udp://
// or an address that does not parse.
std::unique_ptr<VideoInput> make_video_input(boost::asio::io_context& io,
                                             const gimbal::video::VideoUrl& url,
                                             VideoInputOptions options,
                                             VideoInputHandlers handlers);

}  // namespace gimbald::video
