// The configuration file (interface contract section 3) as typed values. parse_config()
// reads JSON text, applies the defaults and validates everything, collecting every problem
// with its JSON path ("gimbals[1].link.baud: must be one of 1200, ...") instead of stopping
// at the first. Ranges and meanings of every key: docs/configuration.md.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "command_config.hpp"
#include "config/fields.hpp"
#include "http/http_config.hpp"
#include "link/link_config.hpp"
#include "log_config.hpp"
#include "mavlink_config.hpp"
#include "mqtt/mqtt_config.hpp"
#include "protocols/protocol_id.hpp"
#include "record/record_config.hpp"
#include "session_config.hpp"
#include "terrain/terrain_config.hpp"
#include "vehicle_config.hpp"
#include "video/video_config.hpp"

namespace gimbal::daemon {

// The protocols are the registry's (lib/protocols).
using Protocol = gimbal::protocols::ProtocolId;
using gimbal::protocols::parse_protocol;
using gimbal::protocols::to_string;

struct GimbalConfig {
    std::string name;
    Protocol protocol = gimbal::protocols::all_protocol_ids.front();
    Link link = SimLink{};
    // The keys its protocol owns (`feed`, `viewpro`, `mavlink`...), declared in
    // lib/protocols/<protocol>/<protocol>_config.hpp and read through the registry: every
    // key, defaults included, as the session reads them.
    nlohmann::json protocol_config = nlohmann::json::object();
    // `video` (contract section 17, daemon/video/video_config.hpp); off unless set.
    std::optional<gimbald::video::VideoConfig> video;
    bool operator==(const GimbalConfig&) const = default;
};

// The sections declared next to what they configure (each with its fields()).
using TerrainConfig = gimbal::terrain::TerrainConfig;

struct Config {
    std::vector<GimbalConfig> gimbals;
    CommandConfig command;
    LaserConfig laser;
    StareConfig stare;
    TelemetryConfig telemetry;
    LogConfig log;
    std::optional<VehicleConfig> vehicle;
    MavlinkConfig mavlink;
    std::optional<MqttConfig> mqtt;
    std::optional<HttpConfig> http;
    std::optional<RecordConfig> record;
    std::optional<TerrainConfig> terrain;
    bool operator==(const Config&) const = default;
};

// One problem found in a configuration, with its JSON path (lib/config/fields.hpp).
using Problem = gimbal::config::Problem;

struct ConfigResult {
    Config config;                  // complete only when ok()
    std::vector<Problem> problems;  // every problem found
    bool ok() const { return problems.empty(); }
};

enum class GimbalsSection {
    required,  // the file defines the gimbals (normal run)
    ignored,   // --sim replaces them: the `gimbals` key may be absent and is not read
};

// A configuration problem found only at start, e.g. a key file that changed after
// --check-config passed: exit 1 (exit_config_error) like any configuration problem (contract
// section 14, v4), so systemd does not restart into it (RestartPreventExitStatus=1).
struct ConfigError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The largest configuration read (contract section 14, v4).
inline constexpr std::size_t max_config_bytes = 1024 * 1024;

// Parses and validates JSON text (at most max_config_bytes, no NUL byte). Never throws.
ConfigResult parse_config(std::string_view text, GimbalsSection gimbals = GimbalsSection::required);
// Reads and parses a file; a file that cannot be read, is not a regular file or is larger
// than max_config_bytes is one problem. Never throws.
ConfigResult load_config_file(const std::string& path,
                              GimbalsSection gimbals = GimbalsSection::required);

// The simulated gimbals of `--sim` (contract section 2): no protocols -> one Orion named
// "sim"; otherwise one gimbal "sim-<protocol>" per protocol, link type sim. Each takes the
// `video` section of the first of `file_gimbals` of its protocol that has one (under --sim,
// parse_config reads only `protocol` and `video` of the file's gimbals).
// A protocol's own keys with every default (a gimbal that sets none of them).
nlohmann::json protocol_defaults(Protocol protocol);

std::vector<GimbalConfig> sim_gimbals(std::span<const Protocol> protocols,
                                      const std::vector<GimbalConfig>& file_gimbals = {});

// The configuration as JSON, every key present (the inverse of parse_config). The command
// token is shown as "***" unless `show_token`.
nlohmann::json to_json(const Config& config, bool show_token = false);

}  // namespace gimbal::daemon
