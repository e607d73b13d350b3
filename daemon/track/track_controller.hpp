// One gimbal's visual tracking (contract section 20) on the io_context: its gimbal-track
// process (track_process.hpp), the `track` and `track_stop` commands, STATE `track` and the
// events track_start, track_lost, track_reacquired and track_end. A track starts with the
// access units since the latest key frame (kept all the time), then the gimbal's access units
// go to gimbal-track as they come (dropped, up to the next key frame, when it cannot take them
// now); each box that comes back drives the track's state machine and, while the
// object is seen, its centre is located on the ground with the gimbal's image geometry (the
// code `locate` uses, terrain when configured) and fed to the ground filter. A track ends
// when stopped, overridden by a client's steering command, lost too long (timeout), or when
// the video or gimbal-track goes away (no_video).
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "command/result.hpp"
#include "gimbal_session.hpp"
#include "link/lifetime.hpp"
#include "metrics/histogram.hpp"
#include "session/track_request.hpp"
#include "state/event.hpp"
#include "state/track_state.hpp"
#include "terrain/elevation_model.hpp"
#include "track/ground/ground_filter.hpp"
#include "track/ground/track_state.hpp"
#include "track/track_process.hpp"
#include "track/track_steering.hpp"
#include "video/gimbal_video.hpp"
#include "video/gop_buffer.hpp"
#include "video/tracking_config.hpp"

namespace gimbald::track {

struct TrackControllerOptions {
    std::string gimbal;
    video::TrackingConfig config;
    std::string program;  // gimbal-track (track_program.hpp)
    // No message from gimbal-track this long while video goes to it: it is hung, and killed.
    double hung_after_s = 10;
    // No box yet this long after the start: the track may be lost (the first key frame and its
    // decoding take up to a key frame interval).
    double first_frame_grace_s = 3;
    std::size_t piece_bytes = 64 * 1024;  // an access unit's pieces on the socket
};

class TrackController {
  public:
    using EventSink = std::function<void(const gimbal::state::Event&)>;
    // What the flight recorder records of a track (docs/recording-format.md): every event,
    // and STATE `track` each time a box from gimbal-track was handled.
    struct RecordTap {
        EventSink event;
        std::function<void(const gimbal::state::TrackState&)> box_handled;
    };

    // `session`, `video` and `terrain` (nullptr: none) must outlive this object.
    TrackController(boost::asio::io_context& io, TrackControllerOptions options,
                    GimbalSession& session, video::GimbalVideo& video,
                    gimbal::terrain::ElevationModel* terrain, EventSink on_event);
    ~TrackController();

    void start();
    void stop();
    void set_record_tap(RecordTap tap) { record_tap_ = std::move(tap); }

    gimbal::command::Result<nlohmann::json> track(const nlohmann::json& request);
    gimbal::command::Result<nlohmann::json> track_stop(const nlohmann::json& request);
    // A client steered the gimbal itself (`cmd`): a running track ends, overridden.
    void overridden(std::string_view cmd);

    // STATE `track`; nullopt when none runs.
    std::optional<gimbal::state::TrackState> state() const;
    const TrackProcess& process() const { return process_; }
    // Frame received -> steering command sent (contract section 20, "Budgets"): for each
    // steering command a box made due, the time from its frame's access unit arriving at
    // gimbald to the command handed to the gimbal's link, in seconds. Commands of the 20 Hz
    // tick are not counted. Metric gimbald_track_steer_latency_seconds (docs/http.md).
    const gimbal::metrics::Histogram& steer_latency() const { return steer_latency_; }

  private:
    struct Track {
        std::uint32_t id = 0;
        gimbal::session::TrackBox box;
        double confidence = 1;
        bool steer = true;
        double started_s = 0;
        std::string started_utc;
        gimbal::track::TrackStateMachine machine;
        gimbal::track::GroundFilter filter;
    };

    double now_s() const;
    void on_ready(bool ready);
    void on_message(const gimbal::track::wire::Message& message);
    void on_box(const gimbal::track::wire::Box& box);
    void on_access_unit(const gimbal::video::AccessUnit& au);
    void forward(const gimbal::video::AccessUnit& au);  // to gimbal-track, while a track runs
    void locate(std::int64_t pts_90k, double x, double y);
    void report(const gimbal::track::TrackChange& change);
    void end(gimbal::track::EndReason reason, bool tell_process);
    void arm_tick();
    // A steering command, when one is due; true when one was sent.
    bool steer(double now);
    // The steering command sent for the box of frame `pts_90k`: its latency, observed.
    void observe_steer_latency(std::int64_t pts_90k);
    void tick();
    void emit(std::string kind, nlohmann::json fields);

    boost::asio::io_context& io_;
    TrackControllerOptions options_;
    GimbalSession& session_;
    video::GimbalVideo& video_;
    gimbal::terrain::ElevationModel* terrain_;
    EventSink on_event_;
    RecordTap record_tap_;
    TrackProcess process_;
    TrackSteering steering_;
    boost::asio::steady_timer tick_timer_;
    std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
    std::optional<Track> track_;
    std::optional<std::uint64_t> viewer_;
    gimbal::video::GopBuffer gop_;  // the access units since the latest key frame
    // The gimbal's image geometry when each recent access unit arrived, by its pts: a box is
    // located with the pose of its own frame.
    struct FramePose {
        std::int64_t pts_90k = 0;
        double arrived_s = 0;
        gimbal::session::ImageView view;
    };
    std::deque<FramePose> frame_poses_;
    const FramePose* frame_pose(std::int64_t pts_90k) const;  // nullptr: not kept
    bool need_key_ = true;     // send nothing until a key frame (after a start or a drop)
    double last_heard_s_ = 0;  // the latest message from gimbal-track
    std::uint64_t units_unanswered_ = 0;  // access units sent since then
    std::uint32_t next_id_ = 1;
    gimbal::metrics::Histogram steer_latency_;
    Lifetime lifetime_;
};

}  // namespace gimbald::track
