#include "protocols/orion/orion_commands.hpp"

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "command/params.hpp"
#include "command/path_request.hpp"
#include "geo/wgs84.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"

namespace gimbal::command {
namespace {

namespace o = gimbal::orion;
constexpr double deg2rad = o::pi / 180.0;

template <class P>
bool add_packet(const P& packet, Plan& plan) {
    o::Payload payload;
    if (!o::encode(packet, payload)) return false;
    WirePacket w;
    w.frame = o::frame_bytes(P::id, payload.view());
    w.sent = {{"id", P::id}, {"len", payload.size}};
    plan.packets.push_back(std::move(w));
    return true;
}

struct Request {
    const nlohmann::json& request;
    JsonParams& p;
    const OrionContext& ctx;
    Plan& plan;
};

using Handler = std::function<void(Request&)>;

void geopoint(Request& r) {
    auto& p = r.p;
    const auto lat = p.number("lat", true);
    const auto lon = p.number("lon", true);
    const auto alt = p.number("alt", true);
    // "terrain" is the daemon's to resolve (session/ground_altitude.hpp) before planning.
    const auto ref = p.choice("alt_ref", false).value_or("wgs84");
    const auto vel = p.numbers("vel_ned", false);
    const auto joystick = p.integer_or("joystick_range_m", 0);
    const bool stare = p.boolean_or("stare", false);
    const bool closure = p.boolean_or("closure", false);
    if (!p.ok()) return;

    if (ref == "terrain")
        return p.fail(code::unavailable, "alt_ref 'terrain' needs gimbald's terrain section");
    double alt_wgs84 = *alt;
    if (ref == "msl") {
        if (!r.ctx.geoid_undulation_m)
            return p.fail(code::unavailable,
                          "alt_ref 'msl' needs the geoid undulation from telemetry, none yet");
        alt_wgs84 += *r.ctx.geoid_undulation_m;
    }
    o::GeopointCmd cmd;
    cmd.target_lat = *lat * deg2rad;
    cmd.target_lon = *lon * deg2rad;
    cmd.target_alt = alt_wgs84;
    if (vel) cmd.target_vel_ned = {(*vel)[0], (*vel)[1], (*vel)[2]};
    cmd.joystick_range_m = static_cast<std::uint16_t>(joystick);
    cmd.options = static_cast<o::GeopointOptions>((stare ? 1 : 0) | (closure ? 2 : 0));
    if (!add_packet(cmd, r.plan)) p.fail(code::internal, "geopoint_cmd did not encode");
}

void path(Request& r) {
    auto read = read_path_request(r.p);
    if (!read) return r.p.fail(read.error().code, read.error().message);
    o::Path path;
    path.point_down = read->down;
    for (const auto& ecef : read->ecef)
        path.points.push_back(o::PathPoint{{ecef.x, ecef.y, ecef.z}});
    path.num_cross_track_steps = static_cast<std::uint8_t>(read->cross_steps);
    path.along_track_step_angle = read->along_step_deg * deg2rad;
    path.cross_track_step_ratio = read->cross_ratio;
    if (!add_packet(path, r.plan)) r.p.fail(code::internal, "path did not encode");
}

void laser(Request& r) {
    auto& p = r.p;
    const auto index = p.integer_or("index", 0);
    const auto enable = p.boolean("enable", true);
    const auto arm = p.boolean("arm", true);
    const auto fire = p.boolean("fire", true);
    const auto on_ms = p.integer_or("on_ms", 0);
    const auto off_ms = p.integer_or("off_ms", 0);
    const auto prf = p.integer_or("prf_code", 0);
    auto password = p.text("password", false).value_or("");
    const bool bypass = p.boolean_or("safety_bypass", false);
    if (!p.ok()) return;

    // The safety rules of contract section 4.2, whatever the client sends.
    if (*fire && !r.ctx.allow_fire)
        return p.fail(code::forbidden, "laser fire is disabled (laser.allow_fire is false)");
    if (*fire && !(*enable && *arm))
        return p.fail(code::bad_request, "'fire': true needs 'enable': true and 'arm': true");
    if (bypass && !r.ctx.allow_safety_bypass)
        return p.fail(code::forbidden,
                      "laser safety bypass is disabled (laser.allow_safety_bypass is false)");

    o::LaserCmd cmd;
    cmd.index = static_cast<std::uint8_t>(index);
    cmd.password = std::move(password);
    cmd.enable = *enable;
    cmd.arm = *arm;
    cmd.fire = *fire;
    cmd.on_time_ms = static_cast<std::uint16_t>(on_ms);
    cmd.off_time_ms = static_cast<std::uint16_t>(off_ms);
    cmd.prf_code = static_cast<std::uint16_t>(prf);
    cmd.safety_bypass = bypass;
    if (!add_packet(cmd, r.plan)) return p.fail(code::internal, "laser_cmd did not encode");

    LaserIntent intent;
    intent.index = cmd.index;
    intent.fire = cmd.fire;
    cmd.fire = false;
    intent.cease_frame = o::to_wire(cmd);
    r.plan.laser = std::move(intent);
}

void pan_tilt(Request& r, o::Mode mode, bool default_stabilized) {
    auto& p = r.p;
    const auto pan = p.number("pan", true);
    const auto tilt = p.number("tilt", true);
    const bool stabilized = p.boolean_or("stabilized", default_stabilized);
    const double impulse = p.number_or("impulse_time_s", 0.0);
    if (!p.ok()) return;
    o::Cmd cmd;
    cmd.cmd.target = {*pan * deg2rad, *tilt * deg2rad};
    cmd.cmd.mode = mode;
    cmd.cmd.stabilized = stabilized;
    cmd.cmd.impulse_time_s = impulse;
    if (!add_packet(cmd, r.plan)) p.fail(code::internal, "cmd did not encode");
}

// The gimbal's home: OrionCmd position at 0, 0 in the aircraft's frame (not stabilized).
void center(Request& r) {
    if (!r.p.ok()) return;
    o::Cmd cmd;
    cmd.cmd.target = {0.0, 0.0};
    cmd.cmd.mode = o::Mode::position;
    cmd.cmd.stabilized = false;
    if (!add_packet(cmd, r.plan)) r.p.fail(code::internal, "cmd did not encode");
}

void mode(Request& r) {
    const auto name = r.p.choice("mode", true);
    if (!r.p.ok()) return;
    o::Cmd cmd;
    o::enum_from_name(*name, cmd.cmd.mode);
    if (!add_packet(cmd, r.plan)) r.p.fail(code::internal, "cmd did not encode");
}

void stare_ack(Request& r) {
    auto& p = r.p;
    const auto time = p.integer("system_time_ms", false);
    if (!p.ok()) return;
    if (!time && !r.ctx.last_stare_time_ms)
        return p.fail(code::unavailable, "no StareStart received yet: give 'system_time_ms'");
    o::StareAck ack;
    ack.echo_system_time_ms = time ? static_cast<std::uint32_t>(*time) : *r.ctx.last_stare_time_ms;
    if (!add_packet(ack, r.plan)) p.fail(code::internal, "stare_ack did not encode");
}

void retract(Request& r) {
    const auto action = r.p.choice("action", true);
    if (!r.p.ok()) return;
    o::RetractCommand cmd;
    o::enum_from_name(*action, cmd.cmd);
    if (!add_packet(cmd, r.plan)) r.p.fail(code::internal, "retract_cmd did not encode");
}

// Commands whose parameters are exactly the packet's JSON keys (camera_switch, camera_zoom,
// range): the packet's own JSON reader checks types and wire ranges.
template <class P>
void packet_command(Request& r, std::initializer_list<std::string_view> required) {
    auto& p = r.p;
    nlohmann::json fields = nlohmann::json::object();
    for (const auto& [key, value] : r.request.items()) {
        if (key == "cmd" || key == "id" || key == "gimbal" || key == "token") continue;
        p.raw(key);  // accounted for: the packet reader rejects keys it does not know
        fields[key] = value;
    }
    for (const auto key : required)
        if (!fields.contains(std::string(key)))
            return p.fail(code::bad_request, "missing parameter '" + std::string(key) + "'");
    P packet;
    o::JsonError error;
    if (!o::from_json(fields, packet, error)) return p.fail(error.code, error.message);
    if (!add_packet(packet, r.plan))
        p.fail(code::internal, std::string(P::name) + " did not encode");
}

// Packets a client may ask the gimbal for with a zero-length request: reports and settings,
// never a command (a zero-length RESET would reset the gimbal).
bool requestable(std::uint8_t id) {
    bool found = false;
    const auto match = [&]<class P>() { found = found || P::id == id; };
    o::for_each_packet_in(o::TelemetryPackets{}, match);
    o::for_each_packet_in(o::ConfigPackets{}, match);
    o::for_each_packet_in(o::VersionPackets{}, match);
    return found || id == o::pkt::laser_states;
}

void request(Request& r) {
    auto& p = r.p;
    const auto name = p.text("packet", true);
    if (!p.ok()) return;
    std::vector<std::uint8_t> ids;
    std::uint8_t id = 0;
    if (*name == "versions") {
        ids = {o::pkt::clevis_version,  o::pkt::crown_version,   o::pkt::payload_version,
               o::pkt::tracker_version, o::pkt::retract_version, o::pkt::lensctl_version};
    } else if (o::packet_id(*name, id) && requestable(id)) {
        ids = {id};
    } else {
        std::string names;
        const auto list = [&]<class P>() {
            names += (names.empty() ? "" : ", ") + std::string(P::name);
        };
        o::for_each_packet_in(o::ConfigPackets{}, list);
        o::for_each_packet_in(o::VersionPackets{}, list);
        return p.fail(code::bad_request,
                      "'packet' must be \"versions\" or a report or settings "
                      "packet name, e.g. " +
                          names);
    }
    for (const auto packet_id : ids) {
        WirePacket w;
        w.frame = o::request_bytes(packet_id);
        w.sent = {{"id", packet_id}, {"len", 0}};
        r.plan.packets.push_back(std::move(w));
    }
}

const std::map<std::string, Handler, std::less<>>& handlers() {
    static const std::map<std::string, Handler, std::less<>> table{
        {"geopoint", geopoint},
        {"path", path},
        {"laser", laser},
        {"position", [](Request& r) { pan_tilt(r, o::Mode::position, false); }},
        {"rate", [](Request& r) { pan_tilt(r, o::Mode::rate, true); }},
        {"center", center},
        {"mode", mode},
        {"stare_ack", stare_ack},
        {"retract", retract},
        {"camera_switch", [](Request& r) { packet_command<o::CameraSwitch>(r, {"index"}); }},
        {"camera_zoom", [](Request& r) { packet_command<o::CameraState>(r, {"zoom"}); }},
        {"range", [](Request& r) { packet_command<o::RangeData>(r, {"range_m"}); }},
        {"request", request},
    };
    return table;
}

}  // namespace

bool is_orion_command(std::string_view cmd) {
    return handlers().count(cmd) != 0;
}

std::optional<Error> plan_orion(std::string_view cmd, const nlohmann::json& request,
                                const OrionContext& context, Plan& plan) {
    const auto it = handlers().find(cmd);
    if (it == handlers().end()) return Error{code::unknown_cmd, "unknown command"};
    JsonParams params(request, cmd);
    Request r{request, params, context, plan};
    it->second(r);
    params.reject_unknown();
    if (!params.ok()) {
        plan = Plan{};  // a refused command sends nothing
        return params.error();
    }
    return std::nullopt;
}

}  // namespace gimbal::command
