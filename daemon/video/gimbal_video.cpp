#include "video/gimbal_video.hpp"

#include <cmath>
#include <stdexcept>

#include "framing/hex.hpp"
#include "klv/local_set.hpp"
#include "klv_state/sensor_frame.hpp"
#include "state/precision.hpp"
#include "state/writer.hpp"
#include "video/url.hpp"

namespace gimbald::video {

namespace gv = gimbal::video;
namespace klv = gimbal::klv;
using nlohmann::json;
using SteadyClock = std::chrono::steady_clock;

namespace {

gv::VideoUrl parse(const std::string& text) {
    auto parsed = gv::parse_video_url(text);
    if (!parsed) throw std::invalid_argument(text + ": " + parsed.error().message);
    return *parsed;
}

std::uint64_t unix_us_now() {
    return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                          std::chrono::system_clock::now().time_since_epoch())
                                          .count());
}

std::string hex(std::span<const std::uint8_t> bytes) {
    return gimbal::framing::to_hex(bytes, gimbal::framing::HexCase::upper);
}

// klv_vs_telemetry is worked out at most this often (it reads the whole STATE).
constexpr double compare_every_s = 0.2;

}  // namespace

GimbalVideo::GimbalVideo(boost::asio::io_context& io, GimbalVideoOptions options)
    : io_(io),
      options_(std::move(options)),
      log_fields_({{"gimbal", options_.gimbal}}),
      generate_timer_(io),
      watch_timer_(io),
      generate_period_(std::chrono::duration_cast<SteadyClock::duration>(
          std::chrono::duration<double>(1.0 / options_.config.klv_rate_hz))),
      track_(options_.klv_stream_fresh_s),
      bad_checksum_log_(gimbal::log::Level::warn, "klv_bad_checksum",
                        "video datagrams with KLV sets with a bad checksum"),
      refused_log_(gimbal::log::Level::warn, "klv_refused",
                   "video datagrams with KLV sets refused"),
      dropped_log_(gimbal::log::Level::warn, "video_dropped", "times video was dropped"),
      generate_error_log_(gimbal::log::Level::warn, "klv_generate_error",
                          "KLV sets not generated") {
    if (!options_.view) throw std::invalid_argument("GimbalVideo needs the gimbal's view");
    const bool klv_off = options_.config.klv == KlvMode::off;
    for (const auto& text : options_.config.outputs) {
        VideoOutputOptions o;
        o.log_fields = log_fields_;
        o.mux.klv = !klv_off;
        outputs_.push_back(make_video_output(io_, parse(text), std::move(o)));
    }
    const gv::VideoUrl input = parse(options_.config.input);
    if (options_.record && input.scheme == gv::UrlScheme::rtsp) {
        // No TS arrives from RTSP: the recording gets the access units muxed as gimbald's
        // outputs would carry them (without KLV: generated sets are recorded on their own).
        gv::MuxerOptions mux;
        mux.klv = false;
        record_mux_ = std::make_unique<gv::TsMuxer>(
            mux, gv::Codec::h264,
            [this](std::span<const std::uint8_t> chunk) { options_.record(chunk, false); });
    }
    VideoInputOptions in = options_.input;
    for (const auto& [k, v] : log_fields_.items()) in.log_fields[k] = v;
    in.klv = options_.config.klv == KlvMode::automatic || options_.config.klv == KlvMode::parse;
    if (options_.config.source) {
        std::string error;
        in.source = parse_source(*options_.config.source, error);
        if (!in.source) throw std::invalid_argument("video.source: " + error);
    }
    VideoInputHandlers handlers;
    handlers.access_unit = [this](const gv::AccessUnit& au, Clock::time_point) {
        on_access_unit(au);
    };
    handlers.klv = [this](gimbal::klv::CheckedSets& sets, Clock::time_point) { on_klv(sets); };
    handlers.connection = [this](bool up) { on_connection(up); };
    if (options_.record && input.scheme == gv::UrlScheme::udp)
        handlers.ts_bytes = [this](std::span<const std::uint8_t> ts, Clock::time_point) {
            options_.record(ts, false);
        };
    input_ = make_video_input(io_, input, std::move(in), std::move(handlers));
}

GimbalVideo::~GimbalVideo() {
    stop();
}

double GimbalVideo::now_s() const {
    return std::chrono::duration<double>(SteadyClock::now() - epoch_).count();
}

void GimbalVideo::start() {
    if (running_) return;
    running_ = true;
    input_->start();
    arm_watch();
    if (options_.config.klv != KlvMode::off) {
        next_generate_ = SteadyClock::now() + generate_period_;
        arm_generate();
    }
}

void GimbalVideo::stop() {
    if (!running_) return;
    running_ = false;
    lifetime_.reset();
    generate_timer_.cancel();
    watch_timer_.cancel();
    input_->stop();
}

void GimbalVideo::on_access_unit(const gv::AccessUnit& au) {
    clock_.video(au.dts ? au.dts : au.pts);
    for (auto& out : outputs_) out->write_video(au);
    if (record_mux_) record_mux_->write_video(au);
    if (viewers_.empty()) return;
    // A copy: a viewer may add or remove viewers while it runs.
    const auto viewers = viewers_;
    for (const auto& [id, viewer] : viewers)
        if (viewers_.contains(id)) viewer(au);
}

std::uint64_t GimbalVideo::add_viewer(Viewer viewer) {
    const auto id = next_viewer_++;
    viewers_.emplace(id, std::move(viewer));
    return id;
}

void GimbalVideo::remove_viewer(std::uint64_t id) {
    viewers_.erase(id);
}

void GimbalVideo::on_klv(gimbal::klv::CheckedSets& checked) {
    const KlvMode mode = options_.config.klv;
    if (mode == KlvMode::off || mode == KlvMode::generate) return;
    const double now = now_s();
    const nlohmann::json fields = {{"gimbal", options_.gimbal},
                                   {"input", gv::redact_userinfo(options_.config.input)}};
    if (checked.bad_checksums > 0) {
        nlohmann::json f = fields;
        f["sets"] = checked.bad_checksums;
        f["total"] = track_.bad_checksums() + checked.bad_checksums;
        bad_checksum_log_.hit("KLV set with a bad checksum in the video stream: ignored", f);
    }
    if (checked.refused > 0) {
        nlohmann::json f = fields;
        f["sets"] = checked.refused;
        f["total"] = track_.refused() + checked.refused;
        refused_log_.hit(
            "KLV set in the video stream refused before decoding (over 64 KiB or 1024 items, "
            "malformed, or too many in one datagram): ignored",
            f);
    }
    const bool any = !checked.sets.empty();
    for (const auto& set : checked.sets) send_klv(set.bytes);
    track_.stream_sets(std::move(checked), now);
    if (!any) return;
    if (now - vs_telemetry_at_s_ >= compare_every_s) {
        vs_telemetry_at_s_ = now;
        const auto own = gimbal::klv_state::sensor_frame(options_.view(), unix_us_now());
        vs_telemetry_ = gimbal::klv_state::compare(*track_.latest_stream_json(), own);
    }
}

void GimbalVideo::send_klv(std::span<const std::uint8_t> set) {
    // TS outputs only while video flows: their KLV's PTS is the latest video DTS.
    const auto pts = connected_ ? clock_.next() : std::nullopt;
    for (auto& out : outputs_) {
        if (!out->transport_stream() || pts) out->write_klv(set, pts);
    }
}

void GimbalVideo::on_connection(bool connected) {
    connected_ = connected;
    if (!connected) clock_.reset();
}

bool GimbalVideo::generating() const {
    switch (options_.config.klv) {
        case KlvMode::generate:
            return true;
        case KlvMode::automatic:
            return !track_.stream_fresh(now_s());
        case KlvMode::parse:
        case KlvMode::off:
            return false;
    }
    return false;
}

void GimbalVideo::arm_generate() {
    generate_timer_.expires_at(next_generate_);
    generate_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (ec || !running_) return;
        generate();
        // A fixed rate without drift; after a stall, skip rather than burst.
        next_generate_ += generate_period_;
        const auto now = SteadyClock::now();
        if (next_generate_ < now) next_generate_ = now + generate_period_;
        arm_generate();
    }));
}

void GimbalVideo::arm_watch() {
    watch_timer_.expires_after(std::chrono::seconds(1));
    watch_timer_.async_wait(lifetime_.wrap([this](const boost::system::error_code& ec) {
        if (ec || !running_) return;
        watch_counters();
        arm_watch();
    }));
}

// What the input refused or dropped on its own (the demuxer's bounds, its queues) is counted
// there; here it becomes log lines, rolled up like the rest.
void GimbalVideo::watch_counters() {
    const VideoInputStatus s = input_->status();
    nlohmann::json fields = {{"gimbal", options_.gimbal},
                             {"input", gv::redact_userinfo(options_.config.input)}};
    const std::uint64_t refused = s.demux.oversized_klv + s.demux.metadata_dropped;
    if (refused > reported_stream_refused_) {
        nlohmann::json f = fields;
        f["units"] = refused - reported_stream_refused_;
        f["total"] = refused;
        refused_log_.hit(
            "KLV in the video stream refused before it was read (a KLV PES over 128 KiB, or a "
            "synchronous metadata AU over 64 KiB or out of order): ignored",
            f);
    }
    reported_stream_refused_ = refused;
    const std::uint64_t dropped = s.dropped_units + s.dropped_datagrams;
    if (dropped > reported_dropped_) {
        nlohmann::json f = fields;
        f["dropped_units"] = s.dropped_units;
        f["dropped_datagrams"] = s.dropped_datagrams;
        dropped_log_.hit(
            "video dropped: an access unit over 8 MiB, or the input's queues were full", f);
    }
    reported_dropped_ = dropped;
    bad_checksum_log_.poll();
    refused_log_.poll();
    dropped_log_.poll();
    generate_error_log_.poll();
}

void GimbalVideo::generate() {
    if (!generating()) return;
    const auto frame =
        gimbal::klv_state::sensor_frame(options_.view(), unix_us_now(), options_.config.mission_id,
                                        visual_track_ ? visual_track_() : std::nullopt);
    if (!gimbal::klv_state::has_position(frame)) return;  // nothing known about the camera yet
    klv::Encoded encoded = klv::encode(klv::sensor_set(frame));
    if (!encoded.ok()) {
        ++generate_errors_;
        generate_error_log_.hit("a generated KLV set did not encode: " + encoded.error().message,
                                {{"gimbal", options_.gimbal}});
        return;
    }
    ++generated_;
    send_klv(*encoded);
    if (options_.record) options_.record(*encoded, true);
    track_.generated(std::move(encoded).value(), now_s());
}

gimbal::state::VideoState GimbalVideo::video_state() const {
    const VideoInputStatus s = input_->status();
    const auto& info = s.stream;
    const auto positive = [](int v) { return v > 0 ? std::optional(v) : std::nullopt; };
    const auto text = [](const std::string& t) {
        return t.empty() ? std::nullopt : std::optional(t);
    };
    gimbal::state::VideoState v;
    v.input = gv::redact_userinfo(options_.config.input);
    v.connected = s.connected;
    if (info.codec) v.codec = std::string(gv::to_string(*info.codec));
    v.width = positive(info.width);
    v.height = positive(info.height);
    if (info.fps) v.fps = gimbal::state::round_decimals(*info.fps, 3);
    v.bitrate_bps = static_cast<std::uint64_t>(std::llround(info.bitrate_bps));
    if (const auto source = track_.source()) v.klv_source = std::string(to_string(*source));
    if (track_.has_latest()) {
        v.klv = track_.latest_json();
        v.klv["age_s"] = gimbal::state::seconds(track_.latest_age_s(now_s()));
    }
    v.klv_sets = track_.sets();
    v.klv_bad_checksums = track_.bad_checksums();
    v.klv_refused = track_.refused() + s.demux.oversized_klv + s.demux.metadata_dropped;
    v.klv_vs_telemetry = vs_telemetry_;
    v.source = text(s.source);
    v.foreign_datagrams = s.foreign_datagrams;
    v.dropped_datagrams = s.dropped_datagrams;
    v.dropped_units = s.dropped_units;
    v.reconnects = s.reconnects;
    v.last_error = text(s.last_error);
    return v;
}

json GimbalVideo::snapshot() const {
    return gimbal::state::write(video_state());
}

gimbal::command::Result<json> GimbalVideo::klv_reply() const {
    const auto* bytes = track_.latest_bytes();
    if (bytes == nullptr)
        return gimbal::command::Error{
            gimbal::command::code::unavailable,
            options_.config.klv == KlvMode::off
                ? "video.klv is \"off\" for gimbal '" + options_.gimbal + "'"
                : "no KLV set yet for gimbal '" + options_.gimbal +
                      "' (none in the stream, and nothing known to generate one from)"};
    json klv = track_.latest_json();
    klv["age_s"] = gimbal::state::seconds(track_.latest_age_s(now_s()));
    const auto source = track_.source();
    return json{{"klv_hex", hex(*bytes)},
                {"klv", std::move(klv)},
                {"klv_source", std::string(to_string(*source))}};
}

}  // namespace gimbald::video
