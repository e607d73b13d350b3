// The configuration file (interface contract section 3) as typed values. parse_config()
// reads JSON text, applies the defaults and validates everything, collecting every problem
// with its JSON path ("gimbals[1].link.baud: must be one of 1200, ...") instead of stopping
// at the first. Ranges and meanings of every key: docs/configuration.md.
#pragma once

#include <boost/asio/ip/address.hpp>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "config/fields.hpp"
#include "http/http_config.hpp"
#include "link/link_config.hpp"
#include "logging.hpp"
#include "mqtt/mqtt_config.hpp"
#include "protocols/protocol_id.hpp"
#include "record/record_config.hpp"
#include "terrain/terrain_config.hpp"
#include "video/video_config.hpp"

namespace gimbal::daemon {

// The protocols are the registry's (lib/protocols).
using Protocol = gimbal::protocols::ProtocolId;
using gimbal::protocols::parse_protocol;
using gimbal::protocols::to_string;

struct GimbalConfig {
    std::string name;
    Protocol protocol = Protocol::orion;
    Link link = SimLink{};
    // The keys its protocol owns (`feed`, `viewpro`, `mavlink`...), declared in
    // lib/protocols/<protocol>/<protocol>_config.hpp and read through the registry: every
    // key, defaults included, as the session reads them.
    nlohmann::json protocol_config = nlohmann::json::object();
    // `video` (contract section 17, daemon/video/video_config.hpp); off unless set.
    std::optional<gimbald::video::VideoConfig> video;
    bool operator==(const GimbalConfig&) const = default;
};

// An address block such as 192.168.1.0/24 or ::1/128.
struct Cidr {
    boost::asio::ip::address network;  // host bits cleared
    unsigned prefix_length = 0;

    // "a.b.c.d/n" (n 0..32), "v6addr/n" (n 0..128), or a bare address (a single host).
    // Host bits are cleared: "127.0.0.1/8" is 127.0.0.0/8.
    static std::optional<Cidr> parse(std::string_view text);
    // IPv4-mapped IPv6 sources (::ffff:a.b.c.d, seen on dual-stack sockets) match IPv4 blocks.
    bool contains(const boost::asio::ip::address& address) const;
    std::string to_string() const;
    bool operator==(const Cidr&) const = default;
};

// command.auth (contract section 10).
enum class AuthMode { none, signed_requests };

// One key of command.keys; `secret` is read from `secret_file` when the file is loaded.
struct CommandKey {
    std::string id;
    std::string secret_file;
    std::vector<std::string> roles;  // observe, control, laser
    std::vector<std::uint8_t> secret;
    bool operator==(const CommandKey&) const = default;
};

struct RateLimitConfig {
    double per_source_hz = 200;
    double burst = 400;
    bool operator==(const RateLimitConfig&) const = default;
};

struct CommandConfig {
    boost::asio::ip::address bind = boost::asio::ip::make_address_v4("127.0.0.1");
    std::uint16_t port = 8760;
    std::vector<Cidr> allow = default_allow();
    std::optional<std::string> token;
    unsigned max_subscribers = 64;
    unsigned max_subscribers_per_host = 16;  // one source address may not fill the table
    AuthMode auth = AuthMode::none;
    std::vector<CommandKey> keys;
    double max_skew_s = 30;
    RateLimitConfig rate_limit;

    // True when a datagram from `source` may be answered (it lies in one of `allow`).
    bool allowed(const boost::asio::ip::address& source) const;
    static std::vector<Cidr> default_allow();
    bool operator==(const CommandConfig&) const = default;
};

struct LaserConfig {
    bool allow_fire = false;
    double fire_timeout_s = 5.0;
    bool allow_safety_bypass = false;
    bool operator==(const LaserConfig&) const = default;
};

struct StareConfig {
    bool auto_ack = false;
    bool operator==(const StareConfig&) const = default;
};

struct TelemetryConfig {
    double stale_after_s = 1.0;
    bool operator==(const TelemetryConfig&) const = default;
};

struct LogConfig {
    log::Level level = log::Level::info;
    log::Format format = log::Format::json;
    std::optional<std::string> file;
    log::Settings settings() const { return {level, format, file}; }
    bool operator==(const LogConfig&) const = default;
};

// MAVLink from the autopilot.
struct UdpSource {
    boost::asio::ip::address bind = boost::asio::ip::make_address_v4("127.0.0.1");
    std::uint16_t port = 14550;
    bool operator==(const UdpSource&) const = default;
};

struct SerialSource {
    std::string device;
    std::uint32_t baud = 0;
    bool operator==(const SerialSource&) const = default;
};

struct VehicleConfig {
    std::variant<UdpSource, SerialSource> source = UdpSource{};
    std::optional<std::uint8_t> system_id;  // empty: the first autopilot heard
    double timeout_s = 1.0;
    bool operator==(const VehicleConfig&) const = default;
};

// MAVLink gimbal manager (contract section 8): the vehicle endpoint becomes two-way.
struct MavlinkConfig {
    bool gimbal_manager = false;
    std::optional<std::uint8_t> system_id;  // empty: vehicle.system_id, else the autopilot's
    std::uint8_t component_id = 154;        // MAV_COMP_ID_GIMBAL
    std::vector<std::string> targets;       // "host:port", UDP
    std::optional<std::string> signing_key_file;
    // false: the endpoint only reports; every command is DENIED (contract section 14).
    bool commands = true;
    // Home altitude MSL (m) for relative-altitude ROIs when no autopilot reports one.
    std::optional<double> home_alt_msl;
    // Where the signing streams' last timestamps survive a restart; null: in
    // $STATE_DIRECTORY (systemd), else nowhere.
    std::optional<std::string> signing_state_file;
    bool operator==(const MavlinkConfig&) const = default;
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

// Parses and validates JSON text. Never throws.
ConfigResult parse_config(std::string_view text, GimbalsSection gimbals = GimbalsSection::required);
// Reads and parses a file; an unreadable file is one problem. Never throws.
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
