// What a gimbal can do, typed, so that consumers (the MAVLink gimbal manager, the console,
// KLV) ask the gimbal instead of naming its protocol - AP_Mount_Backend's set_angle_target /
// set_zoom returning false is the model. Every function is pure: it reads the gimbal's
// STATE (contract section 5, as GimbalSession::snapshot() gives it) and either answers or
// says why not:
//   - an action (point_angles, rate, geopoint, stop, zoom) returns the gimbald request to run
//     through the one request path ({"cmd": ..., parameters}, without "gimbal"), or an Error:
//     `unsupported` (this protocol cannot), `unavailable` (not yet: the STATE lacks what it
//     needs, e.g. no telemetry for an angle left out);
//   - a reading (line_of_sight, view, identity, limits, camera) returns what STATE says, with
//     nullopt for what this gimbal does not report (yet); `image` says why not as an Error.
// Angles are degrees, positions WGS84 degrees and metres above mean sea level (image's camera
// position: above the WGS84 ellipsoid, as image geometry works).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "command/result.hpp"
#include "geo/attitude.hpp"
#include "geo/footprint.hpp"

namespace gimbal::session {

// A request for the request path, or why there is none.
using Request = command::Result<nlohmann::json>;

enum class YawFrame {
    vehicle,  // yaw from the aircraft's nose (pan)
    earth,    // yaw from north: converted with the aircraft's heading
};

// Point at angles. A left-out angle keeps the gimbal's current one.
struct AnglesTarget {
    std::optional<double> pitch_deg;  // tilt, up positive
    std::optional<double> yaw_deg;    // pan, right positive, in `yaw_frame`
    YawFrame yaw_frame = YawFrame::vehicle;
    std::optional<double> vehicle_heading_deg;  // needed for YawFrame::earth
};

struct RateTarget {
    double pitch_dps = 0;
    double yaw_dps = 0;
};

struct GeoTarget {
    double lat_deg = 0;
    double lon_deg = 0;
    double alt_msl_m = 0;
};

enum class ZoomKind {
    range_percent,  // 0 widest .. 100 narrowest
    continuous,     // -1 zoom out .. 1 zoom in (0 stops: the caller sends nothing)
};

struct ZoomTarget {
    ZoomKind kind = ZoomKind::range_percent;
    double value = 0;
};

// Which actions and MAVLink gimbal capability flags (GIMBAL_DEVICE_CAP_FLAGS) apply.
struct Features {
    bool point_angles = false;
    bool rate = false;
    bool geopoint = false;  // can point at a global location (and stop doing so)
    bool zoom = false;
    bool pitch_lock = false;
    bool yaw_lock = false;
    bool yaw_in_earth_frame = false;
    bool infinite_yaw = false;
    // point_angles given both angles, and rate, read nothing from STATE (the gimbal takes
    // absolute angles; a gimbal stepped from where it looks now does not). The MAVLink
    // mapping then skips building STATE for a PITCHYAW, which ground stations send at up to
    // 100 Hz. tests/unit/protocols checks the claim.
    bool absolute_angles = false;
};

struct Identity {
    std::string vendor;
    std::string model;
    std::optional<std::string> firmware;  // as the gimbal reports it, when it has
};

// Mechanical limits, degrees; nullopt: not reported.
struct Limits {
    std::optional<double> pan_min_deg, pan_max_deg;
    std::optional<double> tilt_min_deg, tilt_max_deg;
};

// Where the camera is and what it looks at (MAVLink CAMERA_FOV_STATUS, KLV).
struct View {
    std::optional<double> lat_deg, lon_deg, alt_msl_m;                       // the camera
    std::optional<double> target_lat_deg, target_lon_deg, target_alt_msl_m;  // image centre
    std::optional<double> hfov_deg, vfov_deg;
    std::optional<double> alt_m;  // the camera above the WGS84 ellipsoid, when reported
    // A range to the image centre the gimbal measured (a laser range finder), metres.
    std::optional<double> measured_range_m;
};

// The camera as image geometry needs it (contract section 16: locate, project, point).
struct ImageView {
    // Position above the WGS84 ellipsoid; camera -> NED with any image rotation; full fields
    // of view.
    geo::CameraPose camera;
    std::optional<double> width_px, height_px;  // the image in pixels, when reported
    // The flat world's altitude above the ellipsoid: the gimbal's own target's, when it
    // reports one (the ground where no terrain answers).
    std::optional<double> flat_alt_m;
    // The geoid height above the ellipsoid the gimbal converts MSL altitudes with (a
    // GeoTarget's alt_msl_m), when it reports one.
    std::optional<double> geoid_undulation_m;
};

// The camera (MAVLink CAMERA_INFORMATION); nullopt members: not reported.
struct Camera {
    bool basic_zoom = false;
    std::optional<double> focal_length_mm;  // widest
    std::optional<int> width_px, height_px;
    std::optional<double> sensor_width_mm, sensor_height_mm;
};

class Capabilities {
  public:
    virtual ~Capabilities() = default;

    virtual Features features() const = 0;
    // The names of the actions this gimbal takes, for STATE `capabilities` (point_angles,
    // rate, geopoint, zoom).
    std::vector<std::string> names() const;

    virtual Request point_angles(const nlohmann::json& state, const AnglesTarget& t) const = 0;
    virtual Request rate(const nlohmann::json& state, const RateTarget& t) const = 0;
    virtual Request geopoint(const nlohmann::json& state, const GeoTarget& t) const = 0;
    // Stop pointing at a location: hold where the gimbal looks now.
    virtual Request stop(const nlohmann::json& state) const = 0;
    virtual Request zoom(const nlohmann::json& state, const ZoomTarget& t) const = 0;

    // The camera's line of sight as a rotation from the camera frame (x along the view) to
    // NED.
    virtual std::optional<geo::Quat> line_of_sight(const nlohmann::json& state) const = 0;
    virtual View view(const nlohmann::json& state) const = 0;
    // The image geometry, or unsupported (the gimbal never reports what it needs, such as a
    // field of view) / unavailable (no telemetry yet).
    virtual command::Result<ImageView> image(const nlohmann::json& state) const = 0;
    // The platform's (aircraft's, or the gimbal mount's) attitude as a rotation from its body
    // frame to NED, when the gimbal reports it (KLV platform heading, pitch and roll).
    virtual std::optional<geo::Quat> platform_attitude(const nlohmann::json&) const {
        return std::nullopt;
    }
    virtual Identity identity(const nlohmann::json& state) const = 0;
    virtual Limits limits(const nlohmann::json& state) const = 0;
    virtual Camera camera(const nlohmann::json& state) const = 0;
};

// Helpers the implementations share: STATE lookups that tolerate absent or null keys.
const nlohmann::json* state_at(const nlohmann::json& state,
                               std::initializer_list<const char*> keys);
// A finite number at that path, else nullopt.
std::optional<double> number_at(const nlohmann::json& state,
                                std::initializer_list<const char*> keys);
// Degrees into -180..180.
double wrap180(double deg);
// An Error for a request this protocol cannot make.
Request unsupported(std::string message);
Request unavailable(std::string message);

}  // namespace gimbal::session
