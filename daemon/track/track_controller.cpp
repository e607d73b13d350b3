#include "track/track_controller.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <variant>
#include <vector>

#include "calendar/utc.hpp"
#include "command/params.hpp"
#include "logging.hpp"
#include "session/image_commands.hpp"
#include "state/writer.hpp"
#include "track/wire/assembler.hpp"
#include "track/wire/codec.hpp"

namespace gimbald::track {

namespace wire = gimbal::track::wire;
namespace gt = gimbal::track;
namespace log = gimbal::log;
namespace code = gimbal::command::code;
using gimbal::command::Error;
using gimbal::command::Result;
using nlohmann::json;

namespace {

// The camera poses of the latest frames kept for locating their boxes: 8 s at 30 fps, longer
// than gimbal-track ever takes to answer (it is killed as hung after 10 s without a word).
constexpr std::size_t max_frame_poses = 240;

constexpr double tick_s = 0.05;  // 20 Hz: loss timing and steering

// Frame received -> steering command sent: finer than the request latencies' buckets around
// the budget (30 ms p95, contract section 20), which is one of the bounds.
std::vector<double> steer_latency_buckets_s() {
    return {0.001, 0.002, 0.005, 0.01, 0.015, 0.02, 0.025, 0.03, 0.04,
            0.05,  0.075, 0.1,   0.15, 0.25,  0.5,  1.0,   2.5};
}

// "2026-11-29T09:15:02.123Z": the contract's UTC with milliseconds.
std::string utc_now() {
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now).count();
    std::string text = gimbal::calendar::to_iso8601(
        gimbal::calendar::from_unix_seconds(static_cast<double>(ms / 1000)));
    char fraction[8];
    std::snprintf(fraction, sizeof fraction, ".%03lldZ", static_cast<long long>(ms % 1000));
    text.pop_back();  // the "Z"
    return text + fraction;
}

wire::Codec wire_codec(gimbal::video::Codec c) {
    switch (c) {
        case gimbal::video::Codec::h264:
            return wire::Codec::h264;
        case gimbal::video::Codec::h265:
            return wire::Codec::h265;
    }
    return wire::Codec::h264;
}

std::string_view event_of(gt::TrackChange::Kind kind) {
    switch (kind) {
        case gt::TrackChange::Kind::lost:
            return "track_lost";
        case gt::TrackChange::Kind::reacquired:
            return "track_reacquired";
        case gt::TrackChange::Kind::ended:
            return "track_end";
        case gt::TrackChange::Kind::none:
            break;
    }
    return "";
}

TrackProcessOptions process_options(const TrackControllerOptions& o) {
    TrackProcessOptions p;
    p.gimbal = o.gimbal;
    p.program = o.program;
    return p;
}

}  // namespace

TrackController::TrackController(boost::asio::io_context& io, TrackControllerOptions options,
                                 GimbalSession& session, video::GimbalVideo& video,
                                 gimbal::terrain::ElevationModel* terrain, EventSink on_event)
    : io_(io),
      options_(std::move(options)),
      session_(session),
      video_(video),
      terrain_(terrain),
      on_event_(std::move(on_event)),
      process_(
          io, process_options(options_), [this](const wire::Message& m) { on_message(m); },
          [this](bool ready) { on_ready(ready); }),
      steering_(session, terrain),
      tick_timer_(io),
      steer_latency_(steer_latency_buckets_s()) {}

TrackController::~TrackController() {
    session_.set_track({});  // the session outlives this: its view must not call back
    stop();
}

void TrackController::start() {
    process_.start();
    // Always watching: a track started now begins with the current group of pictures.
    viewer_ = video_.add_viewer(
        lifetime_.wrap([this](const gimbal::video::AccessUnit& au) { on_access_unit(au); }));
}

void TrackController::stop() {
    if (track_) end(gt::EndReason::stopped, false);
    if (viewer_) video_.remove_viewer(*viewer_);
    viewer_.reset();
    lifetime_.reset();
    tick_timer_.cancel();
    process_.stop();
}

double TrackController::now_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
}

Result<json> TrackController::track(const json& request) {
    gimbal::command::JsonParams p(request, "track");
    const auto view = session_.capabilities().image();
    if (!view) {
        p.reject_unknown();
        if (!p.ok()) return p.error();
        return Error{code::unavailable, "no image geometry for gimbal '" + options_.gimbal +
                                            "': " + view.error().message};
    }
    const auto read = gimbal::session::read_track_request(p, *view);
    if (!read) return read.error();
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (!video_.video_state().connected)
        return Error{code::unavailable, "gimbal '" + options_.gimbal + "' has no video now"};
    if (!process_.ready())
        return Error{code::unavailable, "gimbal-track is not running for gimbal '" +
                                            options_.gimbal + "' (it is being restarted)"};

    const std::uint32_t id = next_id_;
    const auto& c = options_.config;
    wire::Start start{id,
                      static_cast<float>(read->box.x0),
                      static_cast<float>(read->box.y0),
                      static_cast<float>(read->box.x1),
                      static_cast<float>(read->box.y1),
                      c.tracker,
                      static_cast<std::uint16_t>(c.width),
                      static_cast<float>(c.lost_after_s),
                      static_cast<float>(c.reacquire_s)};
    const auto bytes = wire::encode(start);
    if (bytes.empty())
        return Error{code::bad_request, "the box cannot be tracked (it leaves the picture)"};
    // A start while a track runs ends that one first, there and here.
    if (track_) end(gt::EndReason::stopped, false);
    if (!process_.send(bytes))
        return Error{code::unavailable, "gimbal-track cannot take a new track now"};
    ++next_id_;
    const double now = now_s();
    track_.emplace(Track{id, read->box, 1.0, read->steer.value_or(c.steer), now, utc_now(),
                         gt::TrackStateMachine({c.lost_after_s, c.reacquire_s}, now),
                         gt::GroundFilter()});
    last_heard_s_ = now;
    units_unanswered_ = 0;
    steering_.reset();
    // The pictures since the latest key frame, at once: gimbal-track decodes them all and
    // starts the tracker on the newest, the picture the box was drawn on (not the next key
    // frame, up to a key frame interval later, when the object has moved on).
    need_key_ = true;
    for (const auto& unit : gop_.units()) forward(unit.view());
    arm_tick();
    const auto s = state();
    const json track_json = gimbal::state::write(*s);
    log::info("track_start", "visual track started",
              {{"gimbal", options_.gimbal},
               {"id", id},
               {"box", track_json["box"]},
               {"steer", track_->steer}});
    emit("track_start", {{"id", id}, {"box", track_json["box"]}, {"steer", track_->steer}});
    return json{{"track", track_json}};
}

Result<json> TrackController::track_stop(const json& request) {
    gimbal::command::JsonParams p(request, "track_stop");
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (!track_) return json{{"stopped", nullptr}};
    const auto id = track_->id;
    end(gt::EndReason::stopped, true);
    return json{{"stopped", id}};
}

void TrackController::overridden(std::string_view cmd) {
    if (!track_) return;
    log::info("track_overridden", "a client steered the gimbal: the track ends",
              {{"gimbal", options_.gimbal}, {"id", track_->id}, {"cmd", std::string(cmd)}});
    end(gt::EndReason::overridden, true);
}

std::optional<gimbal::state::TrackState> TrackController::state() const {
    if (!track_) return std::nullopt;
    const auto& t = *track_;
    const double now = now_s();
    gimbal::state::TrackState s;
    s.id = t.id;
    s.state = t.machine.phase() == gt::TrackPhase::lost ? "lost" : "tracking";
    s.box = {t.box.x0, t.box.y0, t.box.x1, t.box.y1};
    s.centre = {(t.box.x0 + t.box.x1) / 2, (t.box.y0 + t.box.y1) / 2};
    s.confidence = t.confidence;
    if (const auto e = t.filter.estimate(now)) {
        s.ground =
            gimbal::state::TrackGround{e->position.lat_deg, e->position.lon_deg, e->position.alt_m};
        if (e->fixes >= 2)
            s.velocity = gimbal::state::TrackVelocity{e->north_mps, e->east_mps, e->speed_mps,
                                                      e->course_deg};
    }
    s.steer = t.steer;
    s.frames = t.machine.frames();
    s.lost_frames = t.machine.lost_frames();
    s.started_utc = t.started_utc;
    s.age_s = now - t.started_s;
    return s;
}

void TrackController::on_ready(bool ready) {
    // gimbal-track went away: the track cannot go on without its frames.
    if (!ready && track_) end(gt::EndReason::no_video, false);
}

void TrackController::on_message(const wire::Message& message) {
    last_heard_s_ = now_s();
    units_unanswered_ = 0;
    if (const auto* box = std::get_if<wire::Box>(&message)) {
        on_box(*box);
    } else if (const auto* ended = std::get_if<wire::Ended>(&message)) {
        if (track_ && ended->id == track_->id) end(ended->reason, false);
    } else if (const auto* error = std::get_if<wire::Error>(&message)) {
        log::warn("track_process_message", error->message, {{"gimbal", options_.gimbal}});
    }
}

void TrackController::on_box(const wire::Box& box) {
    if (!track_ || box.id != track_->id) return;
    const double now = now_s();
    const bool seen = box.state == wire::BoxState::tracking;
    track_->box = {box.x0, box.y0, box.x1, box.y1};
    track_->confidence = box.confidence;
    const auto change = track_->machine.frame(now, seen);
    // Only a box on the object is located: a lost one is only the image motion's guess.
    if (seen) locate(box.pts_90k, (box.x0 + box.x1) / 2.0, (box.y0 + box.y1) / 2.0);
    report(change);
    if (!track_) return;
    if (record_tap_.box_handled) record_tap_.box_handled(*state());
    // A command due goes out with the box that made it, not at the next tick (up to 50 ms
    // later): frame received -> steering command sent is a budget (contract section 20).
    if (steer(now)) observe_steer_latency(box.pts_90k);
}

const TrackController::FramePose* TrackController::frame_pose(std::int64_t pts_90k) const {
    const auto pose = std::find_if(frame_poses_.rbegin(), frame_poses_.rend(),
                                   [&](const FramePose& p) { return p.pts_90k == pts_90k; });
    return pose == frame_poses_.rend() ? nullptr : &*pose;
}

void TrackController::observe_steer_latency(std::int64_t pts_90k) {
    const FramePose* pose = frame_pose(pts_90k);
    if (pose == nullptr) return;  // too old, or the frame came without a pose
    steer_latency_.observe(std::max(0.0, now_s() - pose->arrived_s));
}

void TrackController::locate(std::int64_t pts_90k, double x, double y) {
    // With the camera's pose when the frame arrived, not now: by now the gimbal may have
    // turned (steering it), and a frame located with a later pose would put the object where
    // the camera went - a loop that runs away.
    const FramePose* pose = frame_pose(pts_90k);
    if (pose == nullptr) return;  // too old, or the frame came without a pose
    const auto ground = gimbal::session::locate_point(pose->view, {x, y}, terrain_);
    if (!ground) return;
    track_->filter.update({pose->arrived_s, ground->point, ground->range_m});
}

void TrackController::on_access_unit(const gimbal::video::AccessUnit& au) {
    gop_.add(au);
    if (const auto view = session_.capabilities().image()) {
        frame_poses_.push_back({static_cast<std::int64_t>(au.pts.value_or(0)), now_s(), *view});
        if (frame_poses_.size() > max_frame_poses) frame_poses_.pop_front();
    }
    forward(au);
}

void TrackController::forward(const gimbal::video::AccessUnit& au) {
    if (!track_ || !process_.ready()) return;
    if (need_key_ && !au.key_frame) return;
    const auto pts = static_cast<std::int64_t>(au.pts.value_or(0));
    const auto pieces = wire::encode_access_unit(pts, au.key_frame, wire_codec(au.codec), au.data,
                                                 options_.piece_bytes);
    for (const auto& piece : pieces) {
        if (!process_.send(piece)) {
            // Behind: the rest of this unit, and every unit up to the next key frame, would
            // only give the decoder broken references.
            need_key_ = true;
            return;
        }
    }
    if (!pieces.empty()) {
        need_key_ = false;
        ++units_unanswered_;
    }
}

void TrackController::report(const gt::TrackChange& change) {
    if (!change || !track_) return;
    if (change.kind == gt::TrackChange::Kind::ended) {
        end(change.reason, true);
        return;
    }
    const auto kind = event_of(change.kind);
    log::info(kind,
              change.kind == gt::TrackChange::Kind::lost ? "visual track lost"
                                                         : "visual track reacquired",
              {{"gimbal", options_.gimbal}, {"id", track_->id}});
    emit(std::string(kind), {{"id", track_->id}});
}

void TrackController::end(gt::EndReason reason, bool tell_process) {
    if (!track_) return;
    const auto id = track_->id;
    track_->machine.end(reason);
    if (tell_process) process_.send(wire::encode(wire::Stop{id}));
    // A client's own command has the gimbal now; otherwise a turning camera stops.
    if (reason != gt::EndReason::overridden) steering_.halt();
    tick_timer_.cancel();
    const json fields{{"id", id},
                      {"reason", std::string(wire::to_string(reason))},
                      {"frames", track_->machine.frames()},
                      {"lost_frames", track_->machine.lost_frames()}};
    track_.reset();
    json logged = fields;
    logged["gimbal"] = options_.gimbal;
    log::info("track_end", "visual track ended", logged);
    emit("track_end", fields);
}

void TrackController::arm_tick() {
    tick_timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(tick_s)));
    tick_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (!ec) tick();
    }));
}

void TrackController::tick() {
    if (!track_) return;
    const double now = now_s();
    // Until the first box, the first key frame may still be on its way (one a second or
    // two): that is not a loss.
    const bool waiting_first =
        track_->machine.frames() == 0 && now - track_->started_s < options_.first_frame_grace_s;
    if (!waiting_first) report(track_->machine.tick(now));
    if (!track_) return;
    // Video goes in, nothing comes back: gimbal-track is hung. Killing it ends the track
    // (no_video) and restarts it.
    if (units_unanswered_ > 0 && now - last_heard_s_ > options_.hung_after_s) {
        process_.kill_process("no answer while video went to it");
        return;
    }
    steer(now);
    arm_tick();
}

bool TrackController::steer(double now) {
    // Steering waits for gimbal-track's first box: until then the gimbal keeps doing what it
    // did (an Orion following the point the operator put it on); turning at a rate towards
    // the requested box would let the platform's own motion sweep the object away.
    if (!track_->steer || track_->machine.frames() == 0) return false;
    const auto& b = track_->box;
    const auto sent = steering_.sent();
    steering_.steer(now, track_->filter.estimate(now), (b.x0 + b.x1) / 2, (b.y0 + b.y1) / 2,
                    track_->machine.phase() != gt::TrackPhase::lost);
    return steering_.sent() != sent;
}

void TrackController::emit(std::string kind, json fields) {
    const gimbal::state::Event event{std::move(kind), std::move(fields)};
    if (record_tap_.event) record_tap_.event(event);
    if (on_event_) on_event_(event);
}

}  // namespace gimbald::track
