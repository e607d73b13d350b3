// One gimbal's video (contract section 17), on the daemon's io_context: the input (UDP TS or
// RTSP, video_input.hpp) feeds the outputs unchanged (video_output.hpp) together with one
// KLV stream - the stream's own UAS Datalink sets, checked and decoded by the input off the
// io thread and kept here (KlvTrack), or sets generated from the gimbal's STATE at
// klv_rate_hz through its capabilities (lib/klv_state) - and, when recording, the recorder
// (the input's TS packets inbound, the generated sets outbound). STATE `video` and the `klv`
// command read it. Nothing is decoded or re-encoded. Threads: none here; a UDP input has its
// worker (ts_worker.hpp) and an RTSP input its reader thread, and both hand small typed
// results to the io thread. The console's video WebSocket taps the access units (VideoTap).
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "command/result.hpp"
#include "klv/sensor_set.hpp"
#include "link/lifetime.hpp"
#include "logging.hpp"
#include "session/gimbal_view.hpp"
#include "state/track_state.hpp"
#include "state/video_state.hpp"
#include "video/klv_clock.hpp"
#include "video/klv_track.hpp"
#include "video/ts_muxer.hpp"
#include "video/video_config.hpp"
#include "video/video_input.hpp"
#include "video/video_output.hpp"
#include "video/video_tap.hpp"

namespace gimbald::video {

struct GimbalVideoOptions {
    std::string gimbal;
    VideoConfig config;
    // The gimbal's typed state (GimbalSession::view): its capabilities and telemetry, read to
    // generate KLV and to compare the stream's KLV with gimbald's own values. Required.
    std::function<gimbal::session::GimbalView()> view;
    // The recorder's tap: the input's MPEG-TS (each UDP datagram; an RTSP input's access
    // units muxed into TS) with generated = false, and each generated set with generated =
    // true. Empty: not recording.
    std::function<void(std::span<const std::uint8_t> bytes, bool generated)> record;
    VideoInputOptions input;          // timeout, backoff, queue (log_fields are filled in)
    double klv_stream_fresh_s = 2.0;  // "auto" generates when no stream set came this long
};

class GimbalVideo final : public VideoTap {
  public:
    // Throws std::invalid_argument when a URL does not parse (the configuration checked it).
    GimbalVideo(boost::asio::io_context& io, GimbalVideoOptions options);
    ~GimbalVideo() override;

    void start();
    void stop();

    // STATE `video`, typed (state/video_state.hpp).
    gimbal::state::VideoState video_state() const;
    // STATE `video` as JSON.
    nlohmann::json snapshot() const;
    // The `klv` command: {"klv_hex", "klv"}, or unavailable when no set is known yet.
    gimbal::command::Result<nlohmann::json> klv_reply() const;

    const KlvTrack& klv() const { return track_; }
    std::uint64_t generated_sets() const { return generated_; }

    // STATE `track` (contract section 20), read when a set is generated: the track goes into
    // it as tags 40-42 and the VMTI set (74). Set by the track controller, created after this.
    void set_visual_track(std::function<std::optional<gimbal::state::TrackState>()> track) {
        visual_track_ = std::move(track);
    }

    std::uint64_t add_viewer(Viewer viewer) override;
    void remove_viewer(std::uint64_t id) override;

  private:
    double now_s() const;
    void on_access_unit(const gimbal::video::AccessUnit& au);
    void on_klv(gimbal::klv::CheckedSets& checked);
    void on_connection(bool connected);
    void send_klv(std::span<const std::uint8_t> set);
    void arm_generate();
    void generate();
    void arm_watch();
    void watch_counters();
    bool generating() const;

    boost::asio::io_context& io_;
    GimbalVideoOptions options_;
    nlohmann::json log_fields_;
    std::unique_ptr<VideoInput> input_;
    std::vector<std::unique_ptr<VideoOutput>> outputs_;
    std::unique_ptr<gimbal::video::TsMuxer> record_mux_;  // RTSP input while recording
    boost::asio::steady_timer generate_timer_;
    boost::asio::steady_timer watch_timer_;  // 1 Hz: counters into log lines, roll-ups
    std::chrono::steady_clock::duration generate_period_;
    std::chrono::steady_clock::time_point next_generate_{};
    Lifetime lifetime_;
    std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
    KlvTrack track_;
    KlvClock clock_;
    bool connected_ = false;
    bool running_ = false;
    std::uint64_t generated_ = 0;
    std::function<std::optional<gimbal::state::TrackState>()> visual_track_;
    std::uint64_t generate_errors_ = 0;
    std::optional<gimbal::state::KlvOffsets> vs_telemetry_;  // until a stream set was compared
    double vs_telemetry_at_s_ = -1e9;
    gimbal::log::RateLimitedLog bad_checksum_log_;
    gimbal::log::RateLimitedLog refused_log_;
    gimbal::log::RateLimitedLog dropped_log_;
    std::uint64_t reported_stream_refused_ = 0;  // input counters already logged
    std::uint64_t reported_dropped_ = 0;
    gimbal::log::RateLimitedLog generate_error_log_;
    std::map<std::uint64_t, Viewer> viewers_;
    std::uint64_t next_viewer_ = 1;
};

}  // namespace gimbald::video
