#include "track/tracking_setup.hpp"

#include <string>

#include "command/catalogue.hpp"
#include "command/params.hpp"
#include "track/track_program.hpp"

namespace gimbald::track {

namespace cmd = gimbal::command;
using nlohmann::json;

namespace {

void attach_unavailable(GimbalSession& session, std::string why) {
    session.add_command("track", [why](const json& request) -> cmd::Result<json> {
        cmd::JsonParams p(request, "track");
        // Its parameters are known here (an unknown key is still bad_request), not read.
        for (const auto& spec : cmd::find_command("track")->params) p.raw(spec.name);
        p.reject_unknown();
        if (!p.ok()) return p.error();
        return cmd::Error{cmd::code::unavailable, why};
    });
    session.add_command("track_stop", [](const json& request) -> cmd::Result<json> {
        cmd::JsonParams p(request, "track_stop");
        p.reject_unknown();
        if (!p.ok()) return p.error();
        return json{{"stopped", nullptr}};
    });
}

}  // namespace

std::unique_ptr<TrackController> attach_tracking(boost::asio::io_context& io,
                                                 GimbalSession& session, video::GimbalVideo* video,
                                                 const std::optional<video::VideoConfig>& config,
                                                 gimbal::terrain::ElevationModel* terrain,
                                                 TrackController::EventSink on_event) {
    if (video == nullptr || !config) {
        attach_unavailable(session, "gimbal '" + session.name() + "' has no video section");
        return nullptr;
    }
    if (!config->tracking) {
        attach_unavailable(session, "gimbal '" + session.name() +
                                        "' has no video.tracking section (visual tracking off)");
        return nullptr;
    }
    TrackControllerOptions options;
    options.gimbal = session.name();
    options.config = *config->tracking;
    options.program = find_track_program();
    auto controller = std::make_unique<TrackController>(io, std::move(options), session, *video,
                                                        terrain, std::move(on_event));
    auto& c = *controller;
    session.add_command("track", [&c](const json& request) { return c.track(request); });
    session.add_command("track_stop", [&c](const json& request) { return c.track_stop(request); });
    // STATE `track`, and through the session's view the MAVLink camera and generated KLV.
    session.set_track([&c] { return c.state(); });
    return controller;
}

}  // namespace gimbald::track
