// The MAVLink camera component of each gimbal (contract section 16): what a ground station's
// camera manager (QGroundControl's, MAVSDK's Camera plugin) asks of a camera, answered from the
// gimbal's typed state and its relayed video (section 17). With visual tracking (section 20:
// video.tracking), MAV_CMD_CAMERA_TRACK_POINT and _TRACK_RECTANGLE become `track` and the
// tracking status messages carry STATE `track`; without, TRACK_POINT becomes the `point`
// command with stare (a held ground point). Pure: the state comes in
// through a lookup, time as time_boot_ms; the daemon executes the requests and sends the
// replies.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gimbal_protocol/commands.hpp"
#include "mavlink/messages.hpp"
#include "state/track_state.hpp"

namespace gimbal::gimbal_protocol {

// One stream a ground station can open: a relayed MPEG-TS output of the gimbal's video.
struct CameraStream {
    std::string name;  // shown by QGroundControl in its stream list
    std::string uri;   // VIDEO_STREAM_INFORMATION.uri
    std::uint8_t type = mavlink::video_stream::type_mpeg_ts;
};

struct ExposedCamera {
    ExposedGimbal gimbal;
    std::uint8_t component_id = mavlink::mav_comp_id_camera;
    bool video = false;      // the gimbal has a `video` section
    bool can_point = false;  // its capabilities point at a location (TRACK_POINT)
    bool can_zoom = false;   // its capabilities zoom (SET_CAMERA_ZOOM)
    // Its video has `tracking`: TRACK_POINT and TRACK_RECTANGLE start a visual track.
    bool visual_tracking = false;
    std::vector<CameraStream> streams;
};

// MAV_COMP_ID_CAMERA + gimbal_device_id - 1: 100..105.
std::uint8_t camera_component(std::uint8_t device_id);

// HEARTBEAT of a camera component: MAV_TYPE_CAMERA, MAV_AUTOPILOT_INVALID, MAV_STATE_ACTIVE.
mavlink::Heartbeat camera_heartbeat();

// What a command does to the camera's click-to-track state, once its requests succeeded.
// `visual`: a visual track started or stopped (its status is STATE `track`, nothing held).
enum class TrackChange : std::uint8_t { none, start, stop, visual };

struct CameraMapped {
    Mapped mapped;
    TrackChange track = TrackChange::none;
    float radius = mavlink::nan_f;  // TRACK_POINT's radius (0..1 of the image width)
};

// The rate of a tracking status stream (MAV_CMD_SET_MESSAGE_INTERVAL), in ms; 0: off.
struct StatusIntervals {
    std::uint32_t image_ms = 0;   // CAMERA_TRACKING_IMAGE_STATUS: off until asked for
    std::uint32_t geo_ms = 1000;  // CAMERA_TRACKING_GEO_STATUS: 1 Hz while a point is held
};

// The point a camera holds after TRACK_POINT, until STOP_TRACKING or another steering.
struct HeldPoint {
    double lat = 0, lon = 0;
    double alt = 0;                 // WGS84 ellipsoid, m
    std::optional<double> alt_msl;  // AMSL, when the gimbal reports its geoid undulation
    float radius = mavlink::nan_f;
};

class CameraComponents {
  public:
    explicit CameraComponents(std::vector<ExposedCamera> cameras);

    const std::vector<ExposedCamera>& cameras() const { return cameras_; }
    const ExposedCamera* find(std::uint8_t component) const;
    bool owns(std::uint8_t component) const { return find(component) != nullptr; }

    // COMMAND_LONG / COMMAND_INT addressed to camera `cam`.
    CameraMapped command(const CommandView& cmd, const ExposedCamera& cam, const StateLookup& state,
                         std::uint32_t time_boot_ms);

    const StatusIntervals& intervals(std::uint8_t component) const {
        return intervals_.at(component);
    }

  private:
    Mapped request(std::uint32_t msgid, float param2, const ExposedCamera& cam,
                   const session::GimbalView& state, std::uint32_t time_boot_ms) const;
    CameraMapped track_point(const CommandView& cmd, const ExposedCamera& cam) const;
    CameraMapped visual_track(const CommandView& cmd, const ExposedCamera& cam) const;
    CameraMapped stop_tracking(const ExposedCamera& cam) const;
    Mapped set_interval(const CommandView& cmd, const ExposedCamera& cam);

    std::vector<ExposedCamera> cameras_;
    std::map<std::uint8_t, StatusIntervals> intervals_;
};

// The messages a camera component sends; camera_device_id 0 (a MAVLink camera with its own
// component id, as common.xml says).
mavlink::CameraInformation camera_component_information(const ExposedCamera& cam,
                                                        const session::GimbalView& state,
                                                        std::uint32_t time_boot_ms);
mavlink::CameraSettings camera_settings(const ExposedCamera& cam, const session::GimbalView& state,
                                        std::uint32_t time_boot_ms);
// No storage: STORAGE_STATUS_NOT_SUPPORTED, count 0 (gimbald records flights, not photos).
mavlink::StorageInformation storage_information(std::uint32_t time_boot_ms);
// Never capturing (no photo or video capture over MAVLink); capacity NaN (unknown).
mavlink::CameraCaptureStatus capture_status(std::uint32_t time_boot_ms);
// Stream `index` (0-based) of the camera's streams, with what STATE `video` says about it.
mavlink::VideoStreamInformation stream_information(const ExposedCamera& cam, std::size_t index,
                                                   const session::GimbalView& state);
mavlink::VideoStreamStatus stream_status(const ExposedCamera& cam, std::size_t index,
                                         const session::GimbalView& state);
mavlink::CameraFovStatus camera_fov_status(const ExposedCamera& cam,
                                           const session::GimbalView& state,
                                           std::uint32_t time_boot_ms);
// While `held`: ACTIVE with the point (altitude AMSL, NaN when unknown) and the distance from
// the camera; without: IDLE.
mavlink::CameraTrackingGeoStatus tracking_geo_status(const std::optional<HeldPoint>& held,
                                                     const session::GimbalView& state);
// `at`: where the held point is in the image now (-1..1, contract section 16), sent as 0..1.
struct ImageAt {
    double x = 0, y = 0;
};
mavlink::CameraTrackingImageStatus tracking_image_status(const std::optional<HeldPoint>& held,
                                                         const std::optional<ImageAt>& at);

// A visual track's status (STATE `track`; nullopt: IDLE). Image: the box and its centre,
// ACTIVE while `tracking`, ERROR while `lost` (the object is not seen; the gimbal coasts on
// its predicted position). Geo: the object's ground position (AMSL when the gimbal reports
// its geoid undulation), velocity and course, and its distance from the camera.
mavlink::CameraTrackingImageStatus visual_tracking_image_status(
    const std::optional<state::TrackState>& track);
mavlink::CameraTrackingGeoStatus visual_tracking_geo_status(
    const std::optional<state::TrackState>& track, const session::GimbalView& state);

}  // namespace gimbal::gimbal_protocol
