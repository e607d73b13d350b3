#include "gimbal_protocol/commands.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geo/attitude.hpp"
#include "gimbal_protocol/status.hpp"
#include "protocols/registry.hpp"
#include "session/capabilities.hpp"

namespace gimbal::gimbal_protocol {

namespace mav = gimbal::mavlink;
using mav::MavResult;

namespace {

constexpr double rad_to_deg = 180.0 / std::numbers::pi;

Mapped answer(MavResult result, std::string reason = {}) {
    Mapped m;
    m.result = result;
    m.reason = std::move(reason);
    return m;
}

// The quaternion's pitch and yaw in degrees (roll is ignored: two-axis gimbals).
struct PitchYaw {
    double pitch_deg, yaw_deg;
};
std::optional<PitchYaw> pitch_yaw_of(const std::array<float, 4>& q) {
    for (const float c : q)
        if (!std::isfinite(c)) return std::nullopt;
    if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) return std::nullopt;
    const auto e = geo::quat_to_euler(geo::Quat{q[0], q[1], q[2], q[3]});
    return PitchYaw{e.pitch_deg, e.yaw_deg};
}

// The request a capability made, addressed to its gimbal.
void add_request(Mapped& out, const ExposedGimbal& g, nlohmann::json request) {
    request["gimbal"] = g.name;
    out.requests.push_back({g.name, std::move(request)});
}

Mapped refusal(const command::Error& e) {
    return answer(result_for_error(e.code), e.message);
}

session::Request unknown_protocol(const ExposedGimbal& g) {
    return session::unsupported(g.name + ": protocol '" + g.protocol + "' is not known");
}

// A command none of the targets takes: the first target's own refusal of the action (the
// capability's "unsupported" and why).
template <class Action>
Mapped refused_by_all(const std::vector<const ExposedGimbal*>& targets, const StateLookup& state,
                      Action action) {
    const ExposedGimbal& g = *targets.front();
    const session::GimbalView view = state(g.name);
    const session::Request r = view.capabilities ? action(*view.capabilities) : unknown_protocol(g);
    return r.ok() ? answer(MavResult::unsupported, "no gimbal takes this") : refusal(r.error());
}

// "CAMERA_INFORMATION comes from the camera component: 100 (main)".
std::string camera_elsewhere(const std::vector<const ExposedGimbal*>& targets) {
    std::string components;
    for (const auto* g : targets)
        components += (components.empty() ? "" : ", ") + std::to_string(g->camera_component) +
                      " (" + g->name + ")";
    return "CAMERA_INFORMATION comes from the camera component: " + components;
}

}  // namespace

std::optional<session::Features> ExposedGimbal::features() const {
    const auto* entry = protocols::find(protocol);
    if (!entry) return std::nullopt;
    return entry->features;
}

std::vector<ExposedGimbal> expose(const std::vector<std::pair<std::string, std::string>>& gimbals,
                                  std::uint8_t first_component) {
    std::vector<std::uint8_t> components{first_component};
    for (int c = first_extra_component; c <= last_extra_component; ++c)
        if (c != first_component) components.push_back(static_cast<std::uint8_t>(c));
    if (components.size() < 6) components.push_back(154);  // first_component was 171..175
    std::vector<ExposedGimbal> out;
    for (const auto& [name, protocol] : gimbals) {
        if (out.size() == 6) break;
        out.push_back(
            {name, protocol, static_cast<std::uint8_t>(out.size() + 1), components[out.size()]});
    }
    return out;
}

CommandView view(const mav::CommandLong& c) {
    CommandView v;
    v.command = c.command;
    std::copy_n(c.param.begin(), 4, v.param.begin());
    v.x = c.param[4];
    v.y = c.param[5];
    v.z = c.param[6];
    v.x_unset = std::isnan(c.param[4]);
    v.y_unset = std::isnan(c.param[5]);
    v.frame = mav::mav_frame::global_relative_alt;
    v.target_system = c.target_system;
    v.target_component = c.target_component;
    return v;
}

CommandView view(const mav::CommandInt& c) {
    CommandView v;
    v.command = c.command;
    v.param = {c.param1, c.param2, c.param3, c.param4};
    constexpr std::int32_t unset = std::numeric_limits<std::int32_t>::max();
    v.x_unset = c.x == unset;
    v.y_unset = c.y == unset;
    v.x = c.x * 1e-7;
    v.y = c.y * 1e-7;
    v.z = c.z;
    v.frame = c.frame;
    v.is_int = true;
    v.target_system = c.target_system;
    v.target_component = c.target_component;
    return v;
}

GimbalManager::GimbalManager(std::vector<ExposedGimbal> gimbals) : gimbals_(std::move(gimbals)) {
    for (const auto& g : gimbals_) controls_[g.device_id];
}

bool GimbalManager::owns(std::uint8_t component) const {
    return std::any_of(gimbals_.begin(), gimbals_.end(),
                       [component](const auto& g) { return g.component_id == component; });
}

std::vector<std::uint8_t> GimbalManager::components() const {
    std::vector<std::uint8_t> out;
    for (const auto& g : gimbals_) out.push_back(g.component_id);
    return out;
}

GimbalManager::Selection GimbalManager::select(std::uint8_t device_id,
                                               std::uint8_t component) const {
    Selection out;
    for (const auto& g : gimbals_) {
        const bool in_scope = component == 0 || g.component_id == component;
        if (in_scope && (device_id == 0 || g.device_id == device_id)) out.gimbals.push_back(&g);
    }
    if (!out.gimbals.empty()) return out;
    out.refusal = "no such gimbal device id";
    for (const auto& g : gimbals_)
        if (g.device_id == device_id)  // ours, but another component manages it
            out.refusal = "gimbal device " + std::to_string(device_id) + " (" + g.name +
                          ") is managed by component " + std::to_string(g.component_id) + ", not " +
                          std::to_string(component);
    return out;
}

GimbalManager::Selection GimbalManager::select(float device_id_param,
                                               std::uint8_t component) const {
    if (std::isnan(device_id_param)) return select(std::uint8_t{0}, component);
    if (!std::isfinite(device_id_param) || device_id_param < 0 || device_id_param > 255 ||
        device_id_param != std::trunc(device_id_param))
        return Selection{{}, "no such gimbal device id"};
    return select(static_cast<std::uint8_t>(device_id_param), component);
}

std::optional<Mapped> GimbalManager::check_control(const std::vector<const ExposedGimbal*>& targets,
                                                   const MavId& sender) {
    for (const auto* g : targets)
        if (!controls_.at(g->device_id).allows(sender)) {
            ++denied_;
            return answer(MavResult::denied, "another system is in control of " + g->name);
        }
    return std::nullopt;
}

Mapped GimbalManager::command(const CommandView& cmd, const MavId& sender,
                              const VehicleView& vehicle, const StateLookup& state,
                              std::uint32_t time_boot_ms) {
    switch (cmd.command) {
        case mav::mav_cmd::do_set_roi_location:
            return roi_location(cmd, sender, vehicle, state);
        case mav::mav_cmd::do_set_roi_none:
            return roi_none(cmd, sender, state);
        case mav::mav_cmd::do_gimbal_manager_pitchyaw: {
            const auto selected = select(cmd.z, cmd.target_component);
            const auto& targets = selected.gimbals;
            if (targets.empty()) return answer(MavResult::denied, selected.refusal);
            const auto flags =
                cmd.x_unset || !std::isfinite(cmd.x) || cmd.x < 0 || cmd.x > 4294967295.0
                    ? std::uint32_t{0}
                    : static_cast<std::uint32_t>(cmd.x);
            return pitchyaw(targets, sender, cmd.param[0], cmd.param[1], cmd.param[2], cmd.param[3],
                            flags, vehicle, state);
        }
        case mav::mav_cmd::do_gimbal_manager_configure:
            return configure(cmd, sender);
        case mav::mav_cmd::set_camera_zoom:
            return zoom(cmd, state);
        case mav::mav_cmd::request_message:
            return request_message(cmd, state, time_boot_ms);
        default:
            return answer(MavResult::unsupported, "command not handled by the gimbal manager");
    }
}

Mapped GimbalManager::message(const mav::Payload& payload, const MavId& sender,
                              const VehicleView& vehicle, const StateLookup& state) {
    if (const auto* py = std::get_if<mav::GimbalManagerSetPitchyaw>(&payload)) {
        const auto selected = select(py->gimbal_device_id, py->target_component);
        const auto& targets = selected.gimbals;
        if (targets.empty()) return answer(MavResult::denied, selected.refusal);
        return pitchyaw(targets, sender, py->pitch * rad_to_deg, py->yaw * rad_to_deg,
                        py->pitch_rate * rad_to_deg, py->yaw_rate * rad_to_deg, py->flags, vehicle,
                        state);
    }
    const auto from_attitude = [&](const Selection& selected, const std::array<float, 4>& q,
                                   float rate_pitch, float rate_yaw, std::uint32_t flags) {
        const auto& targets = selected.gimbals;
        if (targets.empty()) return answer(MavResult::denied, selected.refusal);
        const auto angles = pitch_yaw_of(q);
        const double nan = std::numeric_limits<double>::quiet_NaN();
        return pitchyaw(targets, sender, angles ? angles->pitch_deg : nan,
                        angles ? angles->yaw_deg : nan, rate_pitch * rad_to_deg,
                        rate_yaw * rad_to_deg, flags, vehicle, state);
    };
    if (const auto* sa = std::get_if<mav::GimbalManagerSetAttitude>(&payload))
        return from_attitude(select(sa->gimbal_device_id, sa->target_component), sa->q,
                             sa->angular_velocity_y, sa->angular_velocity_z, sa->flags);
    // A gimbal device has no device id field: its component says which one (0: every one).
    if (const auto* da = std::get_if<mav::GimbalDeviceSetAttitude>(&payload))
        return from_attitude(select(std::uint8_t{0}, da->target_component), da->q,
                             da->angular_velocity_y, da->angular_velocity_z, da->flags);
    return answer(MavResult::unsupported, "message not handled");
}

Mapped GimbalManager::pitchyaw(const std::vector<const ExposedGimbal*>& targets,
                               const MavId& sender, double pitch_deg, double yaw_deg,
                               double pitch_rate, double yaw_rate, std::uint32_t flags,
                               const VehicleView& vehicle, const StateLookup& state) {
    // NaN means "not set"; infinity is never meaningful.
    for (const double v : {pitch_deg, yaw_deg, pitch_rate, yaw_rate})
        if (std::isinf(v)) return answer(MavResult::denied, "infinite parameter");
    const bool angles = !std::isnan(pitch_deg) || !std::isnan(yaw_deg);
    const bool rates = !std::isnan(pitch_rate) || !std::isnan(yaw_rate);
    if (!angles && !rates) return answer(MavResult::denied, "no angle and no rate given");
    if (auto refused = check_control(targets, sender)) return *refused;
    const bool earth_yaw =
        (flags & (mav::gimbal_flags::yaw_lock | mav::gimbal_flags::yaw_in_earth_frame)) != 0;
    const auto given = [](double v) { return std::isnan(v) ? std::nullopt : std::optional(v); };

    Mapped out;
    for (const auto* g : targets) {
        const session::GimbalView view = state(g->name);
        const session::Capabilities* caps = view.capabilities;
        session::Request request = unknown_protocol(*g);
        if (caps && angles) {
            const session::AnglesTarget target{
                given(pitch_deg), given(yaw_deg),
                earth_yaw ? session::YawFrame::earth : session::YawFrame::vehicle,
                vehicle.heading_deg};
            request = caps->point_angles(target);
        } else if (caps) {
            request = caps->rate(session::RateTarget{pitch_rate, yaw_rate});
        }
        if (!request.ok()) {
            // Among several gimbals, one that cannot (a gimbal without rate control) sits
            // this command out.
            if (request.error().code == command::code::unsupported && targets.size() > 1) continue;
            return refusal(request.error());
        }
        add_request(out, *g, std::move(request).value());
    }
    if (out.requests.empty()) return answer(MavResult::unsupported, "no gimbal takes this");
    return out;
}

Mapped GimbalManager::roi_location(const CommandView& cmd, const MavId& sender,
                                   const VehicleView& vehicle, const StateLookup& state) {
    const auto selected = select(cmd.param[0], cmd.target_component);
    const auto& targets = selected.gimbals;
    if (targets.empty()) return answer(MavResult::denied, selected.refusal);
    const auto points = [](const ExposedGimbal* g) {
        const auto f = g->features();
        return f && f->geopoint;
    };
    if (std::none_of(targets.begin(), targets.end(), points))
        return refused_by_all(targets, state,
                              [](const session::Capabilities& c) { return c.geopoint({}); });
    namespace f = mav::mav_frame;
    const std::uint8_t frame = cmd.frame;
    bool relative = false;
    if (frame == f::global || frame == f::global_int)
        relative = false;
    else if (frame == f::global_relative_alt || frame == f::global_relative_alt_int)
        relative = true;
    else
        return answer(MavResult::unsupported, "altitude frame not supported");
    if (cmd.x_unset || cmd.y_unset || !std::isfinite(cmd.x) || !std::isfinite(cmd.y) ||
        !std::isfinite(cmd.z))
        return answer(MavResult::denied, "latitude, longitude and altitude are required");
    if (cmd.x < -90 || cmd.x > 90 || cmd.y < -180 || cmd.y > 180)
        return answer(MavResult::denied, "latitude or longitude out of range");
    if (auto refused = check_control(targets, sender)) return *refused;
    double alt_msl = cmd.z;
    if (relative) {
        if (!vehicle.home_msl_m)
            return answer(MavResult::temporarily_rejected, "home altitude not known yet");
        alt_msl = *vehicle.home_msl_m + cmd.z;
    }
    Mapped out;
    for (const auto* g : targets) {
        if (!points(g)) continue;
        const auto* caps = state(g->name).capabilities;
        auto request =
            caps ? caps->geopoint(session::GeoTarget{cmd.x, cmd.y, alt_msl}) : unknown_protocol(*g);
        if (!request.ok()) return refusal(request.error());
        add_request(out, *g, std::move(request).value());
    }
    return out;
}

Mapped GimbalManager::roi_none(const CommandView& cmd, const MavId& sender,
                               const StateLookup& state) {
    const auto selected = select(cmd.param[0], cmd.target_component);
    const auto& targets = selected.gimbals;
    if (targets.empty()) return answer(MavResult::denied, selected.refusal);
    if (auto refused = check_control(targets, sender)) return *refused;
    Mapped out;
    for (const auto* g : targets) {
        const auto f = g->features();
        if (!f || !f->geopoint) continue;
        const auto* caps = state(g->name).capabilities;
        auto request = caps ? caps->stop() : unknown_protocol(*g);
        if (!request.ok()) return refusal(request.error());
        add_request(out, *g, std::move(request).value());
    }
    if (out.requests.empty())
        return refused_by_all(targets, state,
                              [](const session::Capabilities& c) { return c.stop(); });
    return out;
}

Mapped GimbalManager::configure(const CommandView& cmd, const MavId& sender) {
    const auto selected = select(cmd.z, cmd.target_component);
    const auto& targets = selected.gimbals;
    if (targets.empty()) return answer(MavResult::denied, selected.refusal);
    // Check every target first so a bad parameter changes nothing anywhere.
    std::map<std::uint8_t, Control> next;
    for (const auto* g : targets) {
        Control c = controls_.at(g->device_id);
        if (c.configure(sender, cmd.param[0], cmd.param[1], cmd.param[2], cmd.param[3]) !=
            MavResult::accepted)
            return answer(MavResult::denied, "invalid control parameters");
        next[g->device_id] = c;
    }
    for (auto& [id, c] : next) controls_[id] = c;
    return answer(MavResult::accepted);
}

Mapped GimbalManager::zoom(const CommandView& cmd, const StateLookup& state) {
    const float type = cmd.param[0];
    const float value = cmd.param[1];
    if (!std::isfinite(type) || !std::isfinite(value))
        return answer(MavResult::denied, "zoom type and value must be numbers");
    // Target camera id: 0 all, 1..6 gimbal n's camera (cameras attached to us have no
    // MAVLink component of their own).
    const auto selected =
        select(std::isnan(cmd.param[2]) ? 0.0f : cmd.param[2], cmd.target_component);
    const auto& targets = selected.gimbals;
    if (targets.empty()) return answer(MavResult::denied, "no such camera: " + selected.refusal);
    std::vector<const ExposedGimbal*> zooms;
    for (const auto* g : targets)
        if (const auto f = g->features(); f && f->zoom) zooms.push_back(g);
    if (zooms.empty())
        return refused_by_all(targets, state,
                              [](const session::Capabilities& c) { return c.zoom({}); });
    session::ZoomTarget target{session::ZoomKind::range_percent, value};
    if (type == mav::zoom_type::range) {
        if (value < 0 || value > 100)
            return answer(MavResult::denied, "zoom range is a percentage 0..100");
    } else if (type == mav::zoom_type::continuous) {
        if (value < -1 || value > 1) return answer(MavResult::denied, "continuous zoom is -1..1");
        // Stop (0) leaves the lens where it is.
        if (value == 0) return answer(MavResult::accepted);
        target.kind = session::ZoomKind::continuous;
    } else {
        return answer(MavResult::unsupported, "zoom type not supported");
    }
    Mapped out;
    for (const auto* g : zooms) {
        const auto* caps = state(g->name).capabilities;
        auto request = caps ? caps->zoom(target) : unknown_protocol(*g);
        if (!request.ok()) return refusal(request.error());
        add_request(out, *g, std::move(request).value());
    }
    return out;
}

Mapped GimbalManager::request_message(const CommandView& cmd, const StateLookup& state,
                                      std::uint32_t time_boot_ms) {
    const float id = cmd.param[0];
    if (!std::isfinite(id) || id < 0 || id != std::trunc(id))
        return answer(MavResult::denied, "message id must be a whole number");
    // param2 may name one gimbal device (0 or unset: all).
    const auto selected =
        select(std::isnan(cmd.param[1]) ? 0.0f : cmd.param[1], cmd.target_component);
    const auto& targets = selected.gimbals;
    if (targets.empty()) return answer(MavResult::denied, selected.refusal);
    Mapped out;
    const auto msgid = static_cast<std::uint32_t>(id);
    for (const auto* g : targets) {
        const session::GimbalView s = state(g->name);
        // Each gimbal's messages come from its own manager component.
        const auto reply = [&](mavlink::Payload p) {
            out.replies.push_back(Reply{g->component_id, std::move(p)});
        };
        switch (msgid) {
            case mav::GimbalManagerInformation::id:
                reply(manager_information(*g, s, time_boot_ms));
                break;
            case mav::GimbalDeviceInformation::id:
                reply(device_information(*g, s, time_boot_ms));
                break;
            case mav::CameraInformation::id:
                if (g->camera_component == 0) reply(camera_information(*g, s, time_boot_ms));
                break;
            case mav::GimbalManagerStatus::id:
                reply(manager_status(*g, controls_.at(g->device_id), time_boot_ms));
                break;
            case mav::GimbalDeviceAttitudeStatus::id:
                reply(attitude_status(*g, s, time_boot_ms));
                break;
            case mav::CameraFovStatus::id:
                reply(fov_status(*g, s, time_boot_ms));
                break;
            default:
                return answer(MavResult::unsupported, "message not provided");
        }
    }
    // A gimbal with a camera component of its own is a camera only there (contract v4).
    // common.xml: DENIED is a supported command with a value this component does not support.
    if (msgid == mav::CameraInformation::id && out.replies.empty())
        return answer(MavResult::denied, camera_elsewhere(targets));
    return out;
}

MavResult result_for_error(command::ErrorCode code) {
    namespace c = command::code;
    switch (code) {
        case c::link_down:
        case c::unavailable:
        case c::rate_limited:
            return MavResult::temporarily_rejected;
        case c::unsupported:
            return MavResult::unsupported;
        case c::out_of_range:
        case c::bad_request:
        case c::forbidden:
            return MavResult::denied;
        case c::bad_json:
        case c::too_large:
        case c::unknown_cmd:
        case c::unknown_gimbal:
        case c::busy:
        case c::internal:
            return MavResult::failed;
    }
    return MavResult::failed;
}

MavResult result_for_error(std::string_view code) {
    const auto parsed = command::parse_error_code(code);
    return parsed ? result_for_error(*parsed) : MavResult::failed;
}

std::string_view to_string(MavResult result) {
    switch (result) {
        case MavResult::accepted:
            return "MAV_RESULT_ACCEPTED";
        case MavResult::temporarily_rejected:
            return "MAV_RESULT_TEMPORARILY_REJECTED";
        case MavResult::denied:
            return "MAV_RESULT_DENIED";
        case MavResult::unsupported:
            return "MAV_RESULT_UNSUPPORTED";
        case MavResult::failed:
            return "MAV_RESULT_FAILED";
    }
    return "MAV_RESULT_UNKNOWN";
}

MavResult combine(const std::vector<MavResult>& results) {
    if (results.empty()) return MavResult::failed;
    for (const MavResult r : results)
        if (r == MavResult::accepted) return r;
    return results.front();
}

}  // namespace gimbal::gimbal_protocol
