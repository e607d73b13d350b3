#include "track_session.hpp"

#include <algorithm>
#include <cmath>

#include "track/box.hpp"
#include "track/wire/codec.hpp"

namespace gimbal_track {

using namespace gimbal::track;

struct TrackSession::Track {
    wire::Start request;
    std::unique_ptr<VideoDecoder> decoder;
    std::unique_ptr<ObjectTracker> tracker;
    std::optional<TrackStateMachine> state;
    FrameClock clock;
    std::uint64_t frames = 0;
    std::uint64_t decoder_errors_seen = 0;
};

namespace {

// Logged (and told to gimbald) for the first few, then every so many: a stream of garbage
// must not become a stream of log lines.
bool worth_reporting(std::uint64_t count) {
    return count <= 10 || count % 1000 == 0;
}

float coordinate(double v) {
    if (!std::isfinite(v)) return 0;
    return static_cast<float>(std::clamp(v, -wire::max_coordinate, wire::max_coordinate));
}

}  // namespace

TrackSession::TrackSession(Send send, const Log& log) : send_(std::move(send)), log_(log) {}
TrackSession::~TrackSession() = default;

wire::Hello TrackSession::hello() {
    wire::Hello h;
    for (const auto name : wire::tracker_names) h.trackers.emplace_back(name);
    return h;
}

void TrackSession::refuse(const std::string& error) {
    ++stats_.refused;
    if (!worth_reporting(stats_.refused)) return;
    log_.warn("message_refused", "refused a message from gimbald: " + error,
              {{"refused", stats_.refused}});
    send_(wire::Error{"refused a message: " + error});
}

void TrackSession::datagram(std::span<const std::uint8_t> bytes, bool behind) {
    ++stats_.messages;
    const auto decoded = wire::decode(bytes);
    if (!decoded.message) return refuse(decoded.error);
    std::visit(
        [&](const auto& m) {
            using M = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<M, wire::Start>) {
                start(m);
            } else if constexpr (std::is_same_v<M, wire::Stop>) {
                stop(m);
            } else if constexpr (std::is_same_v<M, wire::AccessUnit>) {
                if (auto unit = assembler_.add(m)) access_unit(*unit, behind);
            } else {
                refuse(std::string(wire::to_string(M::type)) + " is not for gimbal-track");
            }
        },
        *decoded.message);
}

void TrackSession::start(const wire::Start& start) {
    if (track_) end(wire::EndReason::stopped, "another track started");
    track_ = std::make_unique<Track>();
    track_->request = start;
    ++stats_.tracks;
    log_.info("track_start", "tracking, from the next decoded frame",
              {{"id", start.id},
               {"tracker", wire::to_string(start.tracker)},
               {"width", start.width},
               {"box", {start.x0, start.y0, start.x1, start.y1}}});
}

void TrackSession::stop(const wire::Stop& stop) {
    if (!track_ || track_->request.id != stop.id) {
        log_.debug("stop_ignored", "stop for a track not running", {{"id", stop.id}});
        return;
    }
    end(wire::EndReason::stopped, "stopped by gimbald");
}

void TrackSession::shutdown() {
    if (track_) end(wire::EndReason::stopped, "gimbal-track is stopping");
}

void TrackSession::end(wire::EndReason reason, std::string_view why) {
    const auto& t = *track_;
    send_(wire::Ended{t.request.id, reason});
    log_.info(
        "track_end", std::string(why),
        {{"id", t.request.id},
         {"reason", wire::to_string(reason)},
         {"frames", t.frames},
         {"lost_frames", t.state ? t.state->lost_frames() : 0},
         {"decoder", t.decoder ? nlohmann::json{{"frames", t.decoder->stats().frames},
                                                {"errors", t.decoder->stats().errors},
                                                {"corrupt", t.decoder->stats().corrupt},
                                                {"waiting_key", t.decoder->stats().waiting_key}}
                               : nlohmann::json(nullptr)}});
    track_.reset();  // closes the decoder: nothing is decoded without a track
}

void TrackSession::report_decoder_error() {
    auto& t = *track_;
    const auto errors = t.decoder->stats().errors;
    if (errors == t.decoder_errors_seen) return;
    stats_.decoder_errors += errors - t.decoder_errors_seen;
    t.decoder_errors_seen = errors;
    if (worth_reporting(stats_.decoder_errors))
        log_.warn("decoder_error", t.decoder->last_error(),
                  {{"id", t.request.id}, {"errors", stats_.decoder_errors}});
}

bool TrackSession::starting() const {
    return track_ != nullptr && track_->tracker == nullptr;
}

void TrackSession::access_unit(const wire::AccessUnitAssembler::Unit& unit, bool behind) {
    ++stats_.units;
    if (!track_) {
        ++stats_.units_idle;
        return;
    }
    auto& t = *track_;
    if (!t.decoder || t.decoder->codec() != unit.codec) {
        auto opened = VideoDecoder::open(unit.codec, t.request.width);
        if (!opened.decoder) {
            log_.error("decoder_open_failed", opened.error, {{"id", t.request.id}});
            send_(wire::Error{"decoder: " + opened.error});
            end(wire::EndReason::no_video, "no decoder for this video");
            return;
        }
        t.decoder = std::move(opened.decoder);
        log_.info("decoder_open", "decoding while the track runs",
                  {{"id", t.request.id}, {"codec", wire::to_string(unit.codec)}});
    }
    std::vector<DecodedFrame> frames;
    t.decoder->decode(unit.bytes, unit.pts_90k, unit.key, frames);
    report_decoder_error();
    for (std::size_t i = 0; i < frames.size() && track_; ++i) {
        ++stats_.frames;
        // Behind the input: decode everything (later frames need it), track only the newest.
        // The first frame tracked too: gimbald starts a track with the pictures since the
        // latest key frame, and the box belongs to the newest of them.
        const bool newest = i + 1 == frames.size() && !behind;
        if (!newest) {
            ++stats_.skipped;
            continue;
        }
        frame(frames[i]);
    }
}

void TrackSession::frame(DecodedFrame& frame) {
    auto& t = *track_;
    const double now = t.clock.time(frame.pts_90k);
    const double w = frame.bgr.cols, h = frame.bgr.rows;
    FrameResult result;
    if (!t.tracker) {
        const Box image{t.request.x0, t.request.y0, t.request.x1, t.request.y1};
        ObjectTrackerOptions options;
        options.tracker = t.request.tracker;
        auto started = ObjectTracker::start(frame.bgr, from_image(image, w, h), now, options);
        if (!started.tracker) {
            log_.warn("track_refused", started.error, {{"id", t.request.id}});
            send_(wire::Error{"track " + std::to_string(t.request.id) + ": " + started.error});
            end(wire::EndReason::stopped, "the box cannot be tracked");
            return;
        }
        t.tracker = std::move(started.tracker);
        t.state.emplace(TrackTiming{t.request.lost_after_s, t.request.reacquire_s}, now);
        result = started.first;
    } else {
        result = t.tracker->update(frame.bgr, now);
    }
    ++t.frames;
    ++stats_.tracked;
    const auto change = t.state->frame(now, !result.lost);
    const Box image = to_image(result.box, w, h);
    wire::Box box;
    box.id = t.request.id;
    box.pts_90k = frame.pts_90k;
    box.x0 = coordinate(image.x0);
    box.y0 = coordinate(image.y0);
    box.x1 = coordinate(image.x1);
    box.y1 = coordinate(image.y1);
    box.confidence = std::isfinite(result.confidence)
                         ? static_cast<float>(std::clamp(result.confidence, 0.0, 1.0))
                         : 0.0f;
    box.state = result.lost ? wire::BoxState::lost : wire::BoxState::tracking;
    send_(box);
    log_.debug("frame", box.state == wire::BoxState::lost ? "lost" : "tracking",
               {{"id", t.request.id},
                {"pts_90k", frame.pts_90k},
                {"confidence", box.confidence},
                {"tracker_ok", result.parts.tracker_ok},
                {"ncc", result.parts.ncc},
                {"colour", result.parts.colour},
                {"distinct", result.parts.distinctness},
                {"distinct_ratio", result.parts.distinct_ratio},
                {"structure", result.parts.structure},
                {"motion", result.parts.motion},
                {"search", result.search_score},
                {"reacquired", result.reacquired}});
    using Kind = TrackChange::Kind;
    if (change.kind == Kind::lost)
        log_.info("track_lost",
                  result.left_picture ? "the object left the picture" : "confidence too low",
                  {{"id", t.request.id}, {"confidence", box.confidence}, {"t", now}});
    if (change.kind == Kind::reacquired)
        log_.info("track_reacquired", "found again",
                  {{"id", t.request.id}, {"confidence", box.confidence}, {"t", now}});
    if (change.kind == Kind::ended) end(change.reason, "lost for reacquire_s: given up");
}

}  // namespace gimbal_track
