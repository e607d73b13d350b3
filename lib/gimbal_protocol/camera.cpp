#include "gimbal_protocol/camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>

#include "geo/wgs84.hpp"
#include "gimbal_protocol/status.hpp"
#include "session/capabilities.hpp"

namespace gimbal::gimbal_protocol {

namespace mav = gimbal::mavlink;
using mav::MavResult;
namespace cc = mav::camera_cmd;

namespace {

Mapped answer(MavResult result, std::string reason = {}) {
    Mapped m;
    m.result = result;
    m.reason = std::move(reason);
    return m;
}

template <class T>
T clamp_to(double v) {
    return static_cast<T>(
        std::clamp(std::round(v), 0.0, static_cast<double>(std::numeric_limits<T>::max())));
}

// A whole number parameter in 0..max, or nullopt. NaN counts as 0 (MAVSDK and QGroundControl
// leave unused parameters NaN or 0).
std::optional<std::uint32_t> whole(float p, double max) {
    if (std::isnan(p)) return 0;
    if (!std::isfinite(p) || p < 0 || p > max || p != std::trunc(p)) return std::nullopt;
    return static_cast<std::uint32_t>(p);
}

// The streams a stream id selects: 0 all, 1..n one. Empty for another id.
std::vector<std::size_t> streams_for(const ExposedCamera& cam, std::uint32_t stream_id) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < cam.streams.size(); ++i)
        if (stream_id == 0 || stream_id == i + 1) out.push_back(i);
    return out;
}

// The gimbal's video state, when it has reported some.
struct VideoNow {
    float fps = 0;
    std::uint32_t bitrate = 0;
    std::uint16_t width = 0, height = 0;
    std::uint8_t encoding = mav::video_stream::encoding_unknown;
    bool connected = false;
};
VideoNow video_now(const session::GimbalView& state) {
    VideoNow v;
    const auto video = state.video ? state.video() : std::nullopt;
    if (!video) return v;
    v.fps = static_cast<float>(video->fps.value_or(0));
    v.bitrate = clamp_to<std::uint32_t>(static_cast<double>(video->bitrate_bps));
    v.width = clamp_to<std::uint16_t>(video->width.value_or(0));
    v.height = clamp_to<std::uint16_t>(video->height.value_or(0));
    v.connected = video->connected;
    if (video->codec == "h264") v.encoding = mav::video_stream::encoding_h264;
    if (video->codec == "h265") v.encoding = mav::video_stream::encoding_h265;
    return v;
}

std::uint16_t hfov_deg(const session::GimbalView& state) {
    const auto hfov = state.telemetry ? state.telemetry->hfov : std::nullopt;
    return clamp_to<std::uint16_t>(hfov.value_or(0));
}

}  // namespace

std::uint8_t camera_component(std::uint8_t device_id) {
    return static_cast<std::uint8_t>(mav::mav_comp_id_camera + device_id - 1);
}

mav::Heartbeat camera_heartbeat() {
    mav::Heartbeat hb = heartbeat();
    hb.type = mav::mav_type_camera;
    return hb;
}

CameraComponents::CameraComponents(std::vector<ExposedCamera> cameras)
    : cameras_(std::move(cameras)) {
    for (const auto& c : cameras_) intervals_[c.component_id];
}

const ExposedCamera* CameraComponents::find(std::uint8_t component) const {
    for (const auto& c : cameras_)
        if (c.component_id == component) return &c;
    return nullptr;
}

CameraMapped CameraComponents::command(const CommandView& cmd, const ExposedCamera& cam,
                                       const StateLookup& state, std::uint32_t time_boot_ms) {
    const auto& p = cmd.param;
    const auto reply = [&](std::uint32_t msgid, float param2) {
        return CameraMapped{request(msgid, param2, cam, state(cam.gimbal.name), time_boot_ms)};
    };
    // The deprecated request commands (MAVSDK and QGroundControl alternate them with
    // REQUEST_MESSAGE on retries): param1 1 asks, 0 does nothing.
    const auto legacy = [&](std::uint32_t msgid, float flag, float param2) {
        if (flag == 0) return CameraMapped{answer(MavResult::accepted)};
        return reply(msgid, param2);
    };
    switch (cmd.command) {
        case mav::mav_cmd::request_message:
            if (!std::isfinite(p[0]) || p[0] < 0 || p[0] != std::trunc(p[0]))
                return {answer(MavResult::denied, "message id must be a whole number")};
            return reply(static_cast<std::uint32_t>(p[0]), p[1]);
        case cc::request_camera_information:
            return legacy(mav::CameraInformation::id, p[0], 0);
        case cc::request_camera_settings:
            return legacy(mav::CameraSettings::id, p[0], 0);
        case cc::request_storage_information:
            return legacy(mav::StorageInformation::id, p[1], p[0]);
        case cc::request_camera_capture_status:
            return legacy(mav::CameraCaptureStatus::id, p[0], 0);
        case cc::request_video_stream_information:
            return reply(mav::VideoStreamInformation::id, p[0]);
        case cc::request_video_stream_status:
            return reply(mav::VideoStreamStatus::id, p[0]);
        case cc::camera_track_point:
            return cam.visual_tracking ? visual_track(cmd, cam) : track_point(cmd, cam);
        case cc::camera_track_rectangle:
            if (!cam.visual_tracking)
                return {answer(MavResult::unsupported,
                               cam.gimbal.name + " has no visual tracking (video.tracking)")};
            return visual_track(cmd, cam);
        case cc::camera_stop_tracking: {
            const session::GimbalView view = state(cam.gimbal.name);
            if (view.track && view.track()) return stop_tracking(cam);
            if (!cam.can_point)
                return {answer(MavResult::unsupported, cam.gimbal.name + " cannot track a point")};
            // Stop staring and hold where the camera looks (as MAV_CMD_DO_SET_ROI_NONE).
            const auto* caps = state(cam.gimbal.name).capabilities;
            if (!caps) return {answer(MavResult::unsupported, cam.gimbal.name + " cannot stop")};
            auto stop = caps->stop();
            if (!stop.ok())
                return {answer(result_for_error(stop.error().code), stop.error().message)};
            CameraMapped out;
            out.track = TrackChange::stop;
            nlohmann::json r = std::move(stop).value();
            r["gimbal"] = cam.gimbal.name;
            out.mapped.requests.push_back({cam.gimbal.name, std::move(r)});
            return out;
        }
        case cc::set_message_interval:
            return {set_interval(cmd, cam)};
        case cc::video_start_streaming: {
            const auto id = whole(p[0], 255);
            if (!cam.video) return {answer(MavResult::unsupported, "no video configured")};
            if (!id || streams_for(cam, *id).empty())
                return {answer(MavResult::denied, "no such stream")};
            return {answer(MavResult::accepted)};  // it always streams
        }
        case cc::video_stop_streaming:
            return {answer(MavResult::unsupported,
                           "gimbald relays the video continuously (video.outputs)")};
        case cc::set_camera_mode:
            if (p[1] == mav::camera_mode_video) return {answer(MavResult::accepted)};
            return {answer(MavResult::unsupported, "this camera has only video mode")};
        default:
            return {answer(MavResult::unsupported, "command not handled by the camera")};
    }
}

Mapped CameraComponents::request(std::uint32_t msgid, float param2, const ExposedCamera& cam,
                                 const session::GimbalView& state,
                                 std::uint32_t time_boot_ms) const {
    Mapped out;
    const auto send = [&](mav::Payload p) {
        out.replies.push_back(Reply{cam.component_id, std::move(p)});
    };
    switch (msgid) {
        case mav::Heartbeat::id:
            send(camera_heartbeat());
            break;
        case mav::CameraInformation::id:
            send(camera_component_information(cam, state, time_boot_ms));
            break;
        case mav::CameraSettings::id:
            send(camera_settings(cam, state, time_boot_ms));
            break;
        case mav::StorageInformation::id:
            send(storage_information(time_boot_ms));
            break;
        case mav::CameraCaptureStatus::id:
            send(capture_status(time_boot_ms));
            break;
        case mav::CameraFovStatus::id:
            send(camera_fov_status(cam, state, time_boot_ms));
            break;
        case mav::VideoStreamInformation::id:
        case mav::VideoStreamStatus::id: {
            if (cam.streams.empty())
                return answer(MavResult::unsupported,
                              cam.video ? "no MPEG-TS output in video.outputs"
                                        : "no video configured for " + cam.gimbal.name);
            const auto id = whole(param2, 255);
            const auto selected = id ? streams_for(cam, *id) : std::vector<std::size_t>{};
            if (selected.empty()) return answer(MavResult::denied, "no such stream");
            for (const std::size_t i : selected)
                send(msgid == mav::VideoStreamInformation::id
                         ? mav::Payload{stream_information(cam, i, state)}
                         : mav::Payload{stream_status(cam, i, state)});
            break;
        }
        default:
            return answer(MavResult::unsupported, "message not provided by the camera");
    }
    return out;
}

CameraMapped CameraComponents::track_point(const CommandView& cmd, const ExposedCamera& cam) const {
    const auto& p = cmd.param;
    if (!cam.can_point)
        return {answer(MavResult::unsupported, cam.gimbal.name + " cannot point at a location")};
    // param4: the target camera - 0 (or unset) for us, or our own component id.
    if (!std::isnan(p[3]) && p[3] != 0 && p[3] != cam.component_id)
        return {answer(MavResult::denied, "target camera id is not this camera")};
    for (const float v : {p[0], p[1]})
        if (!std::isfinite(v) || v < 0 || v > 1)
            return {answer(MavResult::denied, "point x and y are 0..1")};
    CameraMapped out;
    out.track = TrackChange::start;
    out.radius = std::isfinite(p[2]) && p[2] >= 0 && p[2] <= 1 ? p[2] : mav::nan_f;
    // MAVLink's 0..1 from the top left -> the contract's -1..1 from the centre.
    out.mapped.requests.push_back({cam.gimbal.name,
                                   {{"cmd", "point"},
                                    {"gimbal", cam.gimbal.name},
                                    {"x", 2.0 * static_cast<double>(p[0]) - 1.0},
                                    {"y", 2.0 * static_cast<double>(p[1]) - 1.0},
                                    {"stare", true}}});
    return out;
}

// TRACK_POINT (x, y, radius) or TRACK_RECTANGLE (top left x, y, bottom right x, y), each
// 0..1 from the image's top left, as `track` in the contract's -1..1 from the centre.
CameraMapped CameraComponents::visual_track(const CommandView& cmd,
                                            const ExposedCamera& cam) const {
    const auto& p = cmd.param;
    const bool rectangle = cmd.command == cc::camera_track_rectangle;
    // The target camera: 0 (or unset) for us, or our own component id (param4 of TRACK_POINT,
    // param5 of TRACK_RECTANGLE).
    double target = p[3];
    if (rectangle)  // param5: a COMMAND_INT's x is scaled as degrees from degE7
        target = cmd.x_unset ? std::nan("") : cmd.is_int ? std::round(cmd.x * 1e7) : cmd.x;
    if (!std::isnan(target) && target != 0 && target != cam.component_id)
        return {answer(MavResult::denied, "target camera id is not this camera")};
    const std::size_t corners = rectangle ? 4 : 2;
    for (std::size_t i = 0; i < corners; ++i)
        if (!std::isfinite(p[i]) || p[i] < 0 || p[i] > 1)
            return {answer(MavResult::denied, "image coordinates are 0..1")};
    const auto centred = [&](std::size_t i) { return 2.0 * static_cast<double>(p[i]) - 1.0; };
    nlohmann::json request = {{"cmd", "track"}, {"gimbal", cam.gimbal.name}};
    if (rectangle) {
        if (p[2] <= p[0] || p[3] <= p[1])
            return {answer(MavResult::denied,
                           "the rectangle's bottom right must be below and "
                           "right of its top left")};
        request.update(
            {{"x0", centred(0)}, {"y0", centred(1)}, {"x1", centred(2)}, {"y1", centred(3)}});
    } else {
        request.update({{"x", centred(0)}, {"y", centred(1)}});
        // The radius (a share of the image width) sizes the box: twice it, within track's
        // `size` range; none or 0: track's default.
        if (std::isfinite(p[2]) && p[2] > 0)
            request["size"] = std::clamp(2.0 * static_cast<double>(p[2]), 0.01, 0.5);
    }
    CameraMapped out;
    out.track = TrackChange::visual;
    out.mapped.requests.push_back({cam.gimbal.name, std::move(request)});
    return out;
}

CameraMapped CameraComponents::stop_tracking(const ExposedCamera& cam) const {
    CameraMapped out;
    out.track = TrackChange::visual;
    out.mapped.requests.push_back(
        {cam.gimbal.name, {{"cmd", "track_stop"}, {"gimbal", cam.gimbal.name}}});
    return out;
}

Mapped CameraComponents::set_interval(const CommandView& cmd, const ExposedCamera& cam) {
    const float id = cmd.param[0];
    const float interval_us = cmd.param[1];
    if (id != mav::CameraTrackingImageStatus::id && id != mav::CameraTrackingGeoStatus::id)
        return answer(MavResult::unsupported, "the camera streams only its tracking status");
    if (!std::isfinite(interval_us) || (interval_us < 0 && interval_us != -1))
        return answer(MavResult::denied, "interval must be -1, 0 or microseconds");
    const bool image = id == mav::CameraTrackingImageStatus::id;
    std::uint32_t ms = 0;
    if (interval_us == 0)
        ms = image ? 500 : 1000;  // the defaults: QGroundControl's 2 Hz; the contract's 1 Hz
    else if (interval_us > 0)
        ms = static_cast<std::uint32_t>(
            std::clamp(std::round(interval_us / 1000.0), 100.0, 60000.0));
    auto& intervals = intervals_.at(cam.component_id);
    (image ? intervals.image_ms : intervals.geo_ms) = ms;
    return answer(MavResult::accepted);
}

mav::CameraInformation camera_component_information(const ExposedCamera& cam,
                                                    const session::GimbalView& state,
                                                    std::uint32_t time_boot_ms) {
    mav::CameraInformation c = camera_information(cam.gimbal, state, time_boot_ms);
    namespace f = mav::camera_cap;
    c.flags = 0;
    if (cam.can_zoom) c.flags |= f::has_basic_zoom;
    if (cam.can_point) c.flags |= f::has_tracking_point | f::has_tracking_geo_status;
    if (cam.visual_tracking)
        c.flags |= f::has_tracking_point | f::has_tracking_rectangle | f::has_tracking_geo_status;
    if (cam.video) c.flags |= f::has_video_stream;
    c.gimbal_device_id = cam.gimbal.device_id;
    c.camera_device_id = 0;  // a MAVLink camera with its own component id
    return c;
}

mav::CameraSettings camera_settings(const ExposedCamera&, const session::GimbalView&,
                                    std::uint32_t time_boot_ms) {
    mav::CameraSettings s;
    s.time_boot_ms = time_boot_ms;
    s.mode_id = mav::camera_mode_video;
    return s;  // zoom and focus levels NaN: STATE has no lens position as a percentage
}

mav::StorageInformation storage_information(std::uint32_t time_boot_ms) {
    mav::StorageInformation s;
    s.time_boot_ms = time_boot_ms;
    s.status = mav::storage_status_not_supported;
    return s;
}

mav::CameraCaptureStatus capture_status(std::uint32_t time_boot_ms) {
    mav::CameraCaptureStatus s;
    s.time_boot_ms = time_boot_ms;
    s.available_capacity = mav::nan_f;
    return s;
}

mav::VideoStreamInformation stream_information(const ExposedCamera& cam, std::size_t index,
                                               const session::GimbalView& state) {
    const CameraStream& stream = cam.streams.at(index);
    const VideoNow v = video_now(state);
    mav::VideoStreamInformation s;
    s.framerate = v.fps;
    s.bitrate = v.bitrate;
    s.flags = v.connected ? mav::video_stream::flag_running : 0;
    s.resolution_h = v.width;
    s.resolution_v = v.height;
    s.hfov = hfov_deg(state);
    s.stream_id = static_cast<std::uint8_t>(index + 1);
    s.count = static_cast<std::uint8_t>(cam.streams.size());
    s.type = stream.type;
    mav::set_text(s.name, stream.name);
    mav::set_text(s.uri, stream.uri);
    s.encoding = v.encoding;
    return s;
}

mav::VideoStreamStatus stream_status(const ExposedCamera& cam, std::size_t index,
                                     const session::GimbalView& state) {
    (void)cam.streams.at(index);
    const VideoNow v = video_now(state);
    mav::VideoStreamStatus s;
    s.framerate = v.fps;
    s.bitrate = v.bitrate;
    s.flags = v.connected ? mav::video_stream::flag_running : 0;
    s.resolution_h = v.width;
    s.resolution_v = v.height;
    s.hfov = hfov_deg(state);
    s.stream_id = static_cast<std::uint8_t>(index + 1);
    return s;
}

mav::CameraFovStatus camera_fov_status(const ExposedCamera& cam, const session::GimbalView& state,
                                       std::uint32_t time_boot_ms) {
    mav::CameraFovStatus s = fov_status(cam.gimbal, state, time_boot_ms);
    s.camera_device_id = 0;
    return s;
}

mav::CameraTrackingGeoStatus tracking_geo_status(const std::optional<HeldPoint>& held,
                                                 const session::GimbalView& state) {
    mav::CameraTrackingGeoStatus s;
    if (!held) return s;
    s.tracking_status = mav::tracking::status_active;
    s.lat = static_cast<std::int32_t>(std::lround(held->lat * 1e7));
    s.lon = static_cast<std::int32_t>(std::lround(held->lon * 1e7));
    if (held->alt_msl) s.alt = static_cast<float>(*held->alt_msl);
    // The camera's own position (telemetry: WGS84 ellipsoid altitude).
    const auto* t = state.telemetry;
    if (t && t->lat && t->lon && t->alt) {
        const auto a = geo::lla_to_ecef(geo::Lla{*t->lat, *t->lon, *t->alt});
        const auto b = geo::lla_to_ecef(geo::Lla{held->lat, held->lon, held->alt});
        s.dist = static_cast<float>(std::hypot(a.x - b.x, a.y - b.y, a.z - b.z));
    }
    return s;
}

mav::CameraTrackingImageStatus tracking_image_status(const std::optional<HeldPoint>& held,
                                                     const std::optional<ImageAt>& at) {
    mav::CameraTrackingImageStatus s;
    if (!held) return s;
    s.tracking_status = mav::tracking::status_active;
    s.tracking_mode = mav::tracking::mode_point;
    s.target_data = mav::tracking::target_data_in_status;
    s.radius = held->radius;
    if (at) {
        s.point_x = static_cast<float>((at->x + 1) / 2);
        s.point_y = static_cast<float>((at->y + 1) / 2);
    }
    return s;
}

mav::CameraTrackingImageStatus visual_tracking_image_status(
    const std::optional<state::TrackState>& track) {
    mav::CameraTrackingImageStatus s;
    if (!track) return s;
    s.tracking_status =
        track->state == "tracking" ? mav::tracking::status_active : mav::tracking::status_error;
    s.tracking_mode = mav::tracking::mode_rectangle;
    s.target_data = mav::tracking::target_data_in_status;
    const auto unit = [](double v) { return static_cast<float>((v + 1) / 2); };
    s.point_x = unit(track->centre.x);
    s.point_y = unit(track->centre.y);
    s.rec_top_x = unit(track->box.x0);
    s.rec_top_y = unit(track->box.y0);
    s.rec_bottom_x = unit(track->box.x1);
    s.rec_bottom_y = unit(track->box.y1);
    return s;
}

mav::CameraTrackingGeoStatus visual_tracking_geo_status(
    const std::optional<state::TrackState>& track, const session::GimbalView& state) {
    mav::CameraTrackingGeoStatus s;
    if (!track) return s;
    const std::uint8_t status =
        track->state == "tracking" ? mav::tracking::status_active : mav::tracking::status_error;
    if (!track->ground) {  // not located yet: position unknown (0, 0 and NaN)
        s.tracking_status = status;
        return s;
    }
    HeldPoint at;
    at.lat = track->ground->lat;
    at.lon = track->ground->lon;
    at.alt = track->ground->alt;
    const auto* t = state.telemetry;
    if (t && t->geoid_undulation) at.alt_msl = at.alt - *t->geoid_undulation;
    s = tracking_geo_status(at, state);
    s.tracking_status = status;
    if (track->velocity) {
        s.vel_n = static_cast<float>(track->velocity->north);
        s.vel_e = static_cast<float>(track->velocity->east);
        s.hdg = static_cast<float>(track->velocity->course * std::numbers::pi / 180.0);
    }
    return s;
}

}  // namespace gimbal::gimbal_protocol
