// The commands gimbald answers from the ground and a gimbal's image geometry (contract
// sections 15 and 16): `elevation` (no gimbal), `locate`, `project` and `point`, and the
// terrain's altitudes in `geopoint` and `path` before the gimbal's protocol plans them. The
// request path hands them here after authentication and routing; the pure parts live in
// lib/session (image_commands, ground_altitude) and lib/geo (ground). No protocol is named:
// a gimbal's image and geopoint come from its typed capabilities. A computation that meets
// terrain still being read (terrain_loader.hpp) is `unavailable` ("still being read ...
// retry"), never the flat world's guess.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>

#include "command/result.hpp"
#include "gimbal_session.hpp"
#include "terrain/elevation_model.hpp"

namespace gimbald {

class GroundCommands {
  public:
    // `terrain` (nullptr: none configured) must outlive this object.
    explicit GroundCommands(gimbal::terrain::ElevationModel* terrain) : terrain_(terrain) {}

    // Commands answered here without a gimbal (elevation) and for a gimbal (locate, project,
    // point).
    static bool answers_without_gimbal(std::string_view cmd);
    static bool answers_for_gimbal(std::string_view cmd);

    gimbal::command::Result<nlohmann::json> run(std::string_view cmd,
                                                const nlohmann::json& request);
    GimbalSession::Outcome run(std::string_view cmd, GimbalSession& session,
                               const nlohmann::json& request);

    // A gimbal command's request with the altitudes it leaves to the terrain filled in
    // (unchanged for commands that take none).
    gimbal::command::Result<nlohmann::json> prepare(std::string_view cmd,
                                                    const nlohmann::json& request);

  private:
    // Lookups so far that met a terrain block not read yet (terrain_loader.hpp).
    std::uint64_t misses() const;
    gimbal::command::Result<nlohmann::json> elevation(const nlohmann::json& request);
    GimbalSession::Outcome locate(GimbalSession& session, const nlohmann::json& request,
                                  bool point);
    GimbalSession::Outcome project(GimbalSession& session, const nlohmann::json& request);

    gimbal::terrain::ElevationModel* terrain_;
};

}  // namespace gimbald
