// What a gimbal can do, typed, so that consumers (the MAVLink gimbal manager, the console,
// KLV) ask the gimbal instead of naming its protocol - AP_Mount_Backend's set_angle_target /
// set_zoom returning false is the model. A protocol's capabilities are bound to its typed state
// (its session's Protocol::capabilities()) and read its fields, never STATE JSON; each answer
// is a pure function of that state:
//   - an action (point_angles, rate, geopoint, stop, zoom) returns the gimbald request to run
//     through the one request path ({"cmd": ..., parameters}, without "gimbal"), or an Error:
//     `unsupported` (this protocol cannot), `unavailable` (not yet: the state lacks what it
//     needs, e.g. no telemetry for an angle left out);
//   - a reading (line_of_sight, view, identity, limits, camera) returns what the gimbal
//     reported, with nullopt for what it does not report (yet); `image` says why not as an
//     Error.
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
#include "state/telemetry.hpp"

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
    // point_angles given both angles, and rate, read nothing of what the gimbal reported (the
    // gimbal takes absolute angles; a gimbal stepped from where it looks now does not).
    // tests/unit/protocols checks the claim.
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

// The names of the actions `f` allows, for STATE `capabilities` (point_angles, rate, geopoint,
// zoom).
std::vector<std::string> feature_names(const Features& f);

class Capabilities {
  public:
    virtual ~Capabilities() = default;

    virtual Features features() const = 0;
    std::vector<std::string> names() const { return feature_names(features()); }

    virtual Request point_angles(const AnglesTarget& t) const = 0;
    virtual Request rate(const RateTarget& t) const = 0;
    virtual Request geopoint(const GeoTarget& t) const = 0;
    // Stop pointing at a location: hold where the gimbal looks now.
    virtual Request stop() const = 0;
    virtual Request zoom(const ZoomTarget& t) const = 0;

    // The camera's line of sight as a rotation from the camera frame (x along the view) to
    // NED.
    virtual std::optional<geo::Quat> line_of_sight() const = 0;
    virtual View view() const = 0;
    // The image geometry, or unsupported (the gimbal never reports what it needs, such as a
    // field of view) / unavailable (no telemetry yet).
    virtual command::Result<ImageView> image() const = 0;
    // The platform's (aircraft's, or the gimbal mount's) attitude as a rotation from its body
    // frame to NED, when the gimbal reports it (KLV platform heading, pitch and roll).
    virtual std::optional<geo::Quat> platform_attitude() const { return std::nullopt; }
    virtual Identity identity() const = 0;
    virtual Limits limits() const = 0;
    virtual Camera camera() const = 0;
    // Whether the gimbal says it still points at a location (an Orion in geopoint mode), for a
    // gimbal that reports its pointing mode; nullopt when it reports none (the MAVLink camera
    // then keeps a click-to-track point until steered elsewhere).
    virtual std::optional<bool> holds_geopoint() const { return std::nullopt; }
};

// Helpers the implementations share.
// Degrees into -180..180.
double wrap180(double deg);
// An Error for a request this protocol cannot make.
Request unsupported(std::string message);
Request unavailable(std::string message);

// The catalogue requests of a gimbal gimbald aims itself (a MAVLink device, a SIYI camera),
// whose `position` and `rate` take pan and tilt from the aircraft's nose and whose `geopoint`
// takes an altitude above mean sea level. `current` is where it points now, for an angle left
// out (nullptr before its first report); `who` names it in a message ("device", "camera").
Request nose_angles_request(const AnglesTarget& t, const state::Telemetry* current,
                            std::string_view who);
Request nose_rate_request(const RateTarget& t);
Request msl_geopoint_request(const GeoTarget& t);
// Stop moving: rates 0 0.
Request stop_rates_request();

}  // namespace gimbal::session
