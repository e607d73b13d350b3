// The protocol registry: everything gimbald knows about each gimbal protocol, in one entry
// per protocol (lib/protocols/<name>/<name>_entry.cpp). The daemon, the recorder, the vehicle
// feed, gimbal-sim, gimbal-replay, gimbal-export, gimbalctl and the docs generator ask the
// registry; none of them names a protocol. Adding a protocol: docs/architecture.md.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "config/fields.hpp"
#include "framing/stream_splitter.hpp"
#include "geo/surface.hpp"
#include "protocols/discovery.hpp"
#include "protocols/protocol_id.hpp"
#include "protocols/simulator.hpp"
#include "protocols/track.hpp"
#include "protocols/vehicle_feeder.hpp"
#include "session/capabilities.hpp"
#include "session/protocol.hpp"

namespace gimbal::protocols {

// The daemon-wide settings a session may use (contract section 3: telemetry, stare, laser;
// section 15: terrain).
struct SessionSettings {
    double stale_after_s = 1.0;
    bool auto_ack_stare = false;
    bool allow_fire = false;
    bool allow_safety_bypass = false;
    // The elevation model (nullptr: none configured), shared by every gimbal of the daemon
    // and used on its one io thread: where STATE's footprint and ground meet the ground.
    geo::Surface* terrain = nullptr;
    // The host's UTC clock (seconds), for a protocol that stamps what it sends (MAVLink
    // message signing); the daemon's, or a test's.
    std::function<double()> unix_clock;
    // A secret file's text (a protocol's key), read as the daemon reads every secret file:
    // owner-only, or an error naming the file and why.
    std::function<command::Result<std::string>(const std::string& path)> read_secret;
    // The EGM96 geoid's height above the ellipsoid at a point (metres), for a protocol that
    // turns the vehicle's MSL altitudes into ellipsoid heights itself; nullopt (or an empty
    // function) where no geoid grid is known.
    std::function<std::optional<double>(double lat_deg, double lon_deg)> geoid_undulation;
};

// What reading a protocol's configuration keys may need of the daemon.
struct ConfigContext {
    // As SessionSettings::read_secret: a key file's text, or an error naming the file.
    std::function<command::Result<std::string>(const std::string& path)> read_secret;
};

// A catalogue command (lib/command/catalogue.hpp) this protocol plans, and what it sends.
struct PlannedCommand {
    std::string_view name;
    std::string_view wire;  // for the docs: "GeopointCmd, id 213, 21 bytes"
};

struct Entry {
    ProtocolId id{};
    std::string_view name;          // lower case: configuration, STATE `protocol`, recordings
    std::string_view display_name;  // capitalised: help groups, docs headings
    // The recordings' exported-PDU dissector of its frames; one per protocol, so that
    // find_by_dissector maps a recording's frames back to their entry.
    std::string_view dissector;
    std::span<const PlannedCommand> commands;
    // The top-level STATE keys this protocol's session writes besides the shared ones
    // (state::is_shared_state_key): what a subscriber may name in `keys`.
    std::span<const std::string_view> state_keys;
    // What every gimbal of the protocol can do (a session's capabilities say the same, bound
    // to its state: session::Protocol::capabilities()).
    session::Features features;

    // The gimbal keys this protocol owns besides name, protocol, link and video, declared in
    // its <protocol>_config.hpp. read_config reads them from the gimbal's object, reporting
    // every problem at its path, and returns them written back whole (every key, defaults
    // included). `config_section` is its own object ("viewpro"; empty when it has none), which
    // another protocol's gimbal may not have ("only for protocol ...").
    std::string_view config_section;
    nlohmann::json (*read_config)(config::Fields& gimbal, const ConfigContext& context) = nullptr;

    // `gimbal` is the gimbal's configuration object as config.cpp writes it (to_json): the
    // protocol reads its own keys (read_config's) from it.
    std::unique_ptr<session::Protocol> (*make_session)(const SessionSettings& settings,
                                                       const nlohmann::json& gimbal) = nullptr;
    std::unique_ptr<VehicleFeeder> (*make_feeder)(const nlohmann::json& gimbal) = nullptr;
    // Whether a session of this gimbal will ask SessionSettings::geoid_undulation (the daemon
    // then opens the geoid grid at start); null: never.
    bool (*needs_geoid)(const nlohmann::json& gimbal) = nullptr;
    // The gimbal-to-ground stream split as its framer splits it (the flight recorder).
    std::unique_ptr<framing::StreamSplitter> (*make_splitter)() = nullptr;
    // The gimbal-to-ground stream as track points (gimbal-export).
    std::unique_ptr<TrackDecoder> (*make_track_decoder)() = nullptr;
    // How gimbald finds such a gimbal by UDP broadcast (a TCP link with host "discover");
    // empty: it cannot, and the configuration refuses "discover".
    Discovery discovery;
    Simulator simulator;

    bool plans(std::string_view cmd) const;
};

const Entry& entry(ProtocolId id);
// Every protocol's entry, in all_protocol_ids order.
std::vector<const Entry*> entries();
const Entry* find(std::string_view name);
const Entry* find_by_dissector(std::string_view dissector);
// The protocols' names, in all_protocol_ids order.
std::vector<std::string> names();
// The names joined by ", " (for messages and help texts).
std::string names_text();
// True for a top-level STATE key of some gimbal: a shared key or a protocol's own
// (Entry::state_keys). What `keys` of state, subscribe and mqtt.state_keys may name.
bool is_state_key(std::string_view key);
// The protocols that plan `cmd`, in order.
std::vector<const Entry*> planners_of(std::string_view cmd);

}  // namespace gimbal::protocols
