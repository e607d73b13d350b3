// A gimbal's video input (contract section 17): MPEG-TS over UDP (unicast or multicast) or
// RTSP. Both deliver access units (Annex B, with SPS/PPS before key frames) and, from TS,
// the stream's KLV sets already checked and decoded, on the daemon's io_context; report
// connected/disconnected (data within a timeout), and reconnect or rejoin with backoff.
// No video is decoded. The bytes themselves are taken apart off the io thread (contract
// section 14 v4): TS on its input's worker (ts_worker.hpp), RTSP on its reader thread; what
// waits for the io thread is bounded in count and bytes.
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

#include "klv/checked_sets.hpp"
#include "link/backoff.hpp"
#include "video/codec.hpp"
#include "video/source_pin.hpp"
#include "video/stream_info.hpp"
#include "video/ts_demuxer.hpp"
#include "video/url.hpp"

namespace gimbald::video {

using Clock = std::chrono::steady_clock;

struct VideoInputOptions {
    double timeout_s = 2.0;  // no data this long: disconnected (the URL's timeout_s wins)
    BackoffOptions backoff{0.5, 10.0, 0.2};
    // Access units handed to the io_context and not yet handled, in count and in bytes
    // together; past either, units are dropped and counted (dropped_units).
    std::size_t max_queued_units = 64;
    std::size_t max_queued_bytes = 12u << 20;
    // TS inputs: datagrams waiting for the worker (the oldest dropped past either).
    std::size_t max_queued_datagrams = 1024;
    std::size_t max_queued_datagram_bytes = 4u << 20;
    // TS inputs: check and decode the stream's KLV (false: its KLV units are ignored).
    bool klv = true;
    // UDP inputs: the sender to take the stream from (none: the first, pinned while it sends).
    std::optional<SourceSpec> source;
    double source_silence_s = 5.0;
    // RTSP: redirects followed for one connection (a loop is an error after this many).
    int max_redirects = 4;
    nlohmann::json log_fields = nlohmann::json::object();  // added to every log line
};

struct VideoInputStatus {
    std::string input;  // the URL as configured
    bool connected = false;
    gimbal::video::StreamInfo stream;               // codec, size, fps, bit rate, counts
    std::optional<gimbal::video::KlvCarriage> klv;  // the stream carries KLV (TS inputs)
    gimbal::video::DemuxStats demux;                // TS inputs: CC errors, junk, drops...
    std::uint64_t klv_units = 0;
    std::uint64_t reconnects = 0;  // attempts after the first (RTSP) or reopens (UDP)
    // Access units (and KLV sets) not handed on: over max_access_unit_bytes, or the io thread
    // behind (max_queued_units / max_queued_bytes).
    std::uint64_t dropped_units = 0;
    std::uint64_t dropped_datagrams = 0;  // UDP: the worker behind, the oldest dropped
    std::uint64_t foreign_datagrams = 0;  // UDP: from another sender than the source
    std::string source;                   // UDP: the sender in use, "ADDR:PORT"; empty: none yet
    std::string last_error;               // the latest failure; empty: none
};

struct VideoInputHandlers {
    std::function<void(const gimbal::video::AccessUnit&, Clock::time_point arrival)> access_unit;
    // TS inputs: the KLV sets of the stream's units, checked and decoded (klv::check_sets);
    // the handler may move from it.
    std::function<void(gimbal::klv::CheckedSets&, Clock::time_point arrival)> klv;
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
