#include "ground_commands.hpp"

#include <string>

#include "command/params.hpp"
#include "session/ground_altitude.hpp"
#include "session/image_commands.hpp"
#include "state/ground_json.hpp"
#include "state/precision.hpp"

namespace gimbald {

namespace cmdns = gimbal::command;
namespace session = gimbal::session;
using cmdns::Error;
using nlohmann::json;
namespace code = gimbal::command::code;

namespace {

GimbalSession::Outcome failed(Error e) {
    GimbalSession::Outcome out;
    out.error = std::move(e);
    return out;
}

// The terrain's blocks are read on the loader thread (terrain_loader.hpp); a computation that
// met one not read yet answers this rather than a guess or the flat world.
Error still_loading(const std::string& what) {
    return {code::unavailable,
            "the terrain " + what + " is still being read from its files: retry in a moment"};
}

// Built by appending: GCC 12 -O3 reports a false -Wrestrict for "'" + std::string(...).
Error not_ours(std::string_view cmd) {
    std::string message = "'";
    message += cmd;
    message += "' is not a ground command";
    return {code::internal, std::move(message)};
}

}  // namespace

bool GroundCommands::answers_without_gimbal(std::string_view cmd) {
    return cmd == "elevation";
}

bool GroundCommands::answers_for_gimbal(std::string_view cmd) {
    return cmd == "locate" || cmd == "project" || cmd == "point";
}

cmdns::Result<json> GroundCommands::run(std::string_view cmd, const json& request) {
    if (cmd == "elevation") return elevation(request);
    return not_ours(cmd);
}

GimbalSession::Outcome GroundCommands::run(std::string_view cmd, GimbalSession& session,
                                           const json& request) {
    if (cmd == "locate") return locate(session, request, false);
    if (cmd == "point") return locate(session, request, true);
    if (cmd == "project") return project(session, request);
    return failed(not_ours(cmd));
}

std::uint64_t GroundCommands::misses() const {
    return terrain_ ? terrain_->cache_stats().misses : 0;
}

cmdns::Result<json> GroundCommands::prepare(std::string_view cmd, const json& request) {
    if (!session::takes_ground_altitudes(cmd)) return request;
    const auto before = misses();
    auto prepared = session::resolve_ground_altitudes(cmd, request, terrain_);
    if (!prepared && misses() != before)
        return Error{code::unavailable,
                     still_loading("under the point").message + " (or give 'alt')"};
    return prepared;
}

cmdns::Result<json> GroundCommands::elevation(const json& request) {
    cmdns::JsonParams p(request, "elevation");
    const auto lat = p.number("lat", true);
    const auto lon = p.number("lon", true);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (!terrain_)
        return Error{code::unavailable, "no terrain is configured (the terrain section)"};
    const auto before = misses();
    const auto e = terrain_->elevation(*lat, *lon);
    if (!e && misses() != before)
        return still_loading("at " + cmdns::format_number(*lat) + ", " +
                             cmdns::format_number(*lon));
    if (!e)
        return Error{code::unavailable, "no terrain at " + cmdns::format_number(*lat) + ", " +
                                            cmdns::format_number(*lon) +
                                            " (outside the elevation model, or nodata)"};
    using gimbal::state::metres;
    return json{{"lat", *lat},
                {"lon", *lon},
                {"alt", metres(e->alt_m)},
                {"alt_msl", e->alt_msl_m ? json(metres(*e->alt_msl_m)) : json(nullptr)},
                {"source", e->source}};
}

GimbalSession::Outcome GroundCommands::locate(GimbalSession& session, const json& request,
                                              bool point) {
    cmdns::JsonParams p(request, point ? "point" : "locate");
    const auto position = session::read_image_position(p);
    const bool stare = point && p.boolean_or("stare", false);
    p.reject_unknown();
    if (!p.ok()) return failed(p.error());
    if (!position) return failed(position.error());

    const auto& capabilities = session.capabilities();
    const auto view = capabilities.image();
    if (!view) return failed(view.error());
    const auto at = session::image_point(*position, *view);
    if (!at) return failed(at.error());
    const auto before = misses();
    const auto ground = session::locate_point(*view, *at, terrain_);
    // Met unread terrain before the ground: the flat world's point (or none) is not the answer.
    if (misses() != before && (!ground || ground->surface != gimbal::geo::SurfaceKind::terrain))
        return failed(still_loading("along the line of sight"));
    if (!ground) return failed(ground.error());
    json located = gimbal::state::ground_point_json(*ground);
    if (!point) {
        GimbalSession::Outcome out;
        out.results = std::move(located);
        return out;
    }
    auto pointing = session::point_request(capabilities, *view, *ground, stare);
    if (!pointing) return failed(pointing.error());
    const std::string cmd = pointing->value("cmd", std::string());
    if (!session.supports(cmd))
        return failed({code::internal, "the gimbal's geopoint capability asked for '" + cmd +
                                           "', which its protocol does not plan"});
    auto outcome = session.execute(cmd, *pointing);
    if (outcome.error) return outcome;
    // The reply: the point, then what was sent.
    for (auto& [key, value] : located.items()) outcome.results[key] = std::move(value);
    return outcome;
}

GimbalSession::Outcome GroundCommands::project(GimbalSession& session, const json& request) {
    cmdns::JsonParams p(request, "project");
    const auto lat = p.number("lat", true);
    const auto lon = p.number("lon", true);
    const auto alt = p.number("alt", true);
    p.reject_unknown();
    if (!p.ok()) return failed(p.error());
    const auto view = session.capabilities().image();
    if (!view) return failed(view.error());
    const auto before = misses();
    GimbalSession::Outcome out;
    out.results = session::project_reply(*view, {*lat, *lon, *alt}, terrain_);
    // Whether the terrain hides the point is not known yet.
    if (misses() != before) return failed(still_loading("between the camera and the point"));
    return out;
}

}  // namespace gimbald
