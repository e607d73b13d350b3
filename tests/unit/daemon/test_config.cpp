// Configuration file: the shipped examples, defaults, every validation rule with its exact
// path and message, unknown keys at every level, CIDR matching and the --sim gimbals.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "config.hpp"
#include "protocols/mavlink_device/mavlink_device_config.hpp"
#include "protocols/orion/orion_config.hpp"
#include "protocols/viewpro/viewpro_config.hpp"
#include "video/video_config.hpp"

using namespace gimbal::daemon;
using gimbal::protocols::MavlinkDeviceConfig;
using gimbal::protocols::OrionConfig;
using gimbal::protocols::ViewproConfig;
using gimbal::protocols::ViewproFeed;
using nlohmann::json;

namespace {

const std::string source_dir = GIMBAL_SOURCE_DIR;

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

json read_json(const std::string& path) {
    return json::parse(read_text(path));
}

std::vector<std::string> problem_texts(const ConfigResult& result) {
    std::vector<std::string> texts;
    for (const auto& p : result.problems) texts.push_back(p.text());
    return texts;
}

std::string joined(const std::vector<std::string>& texts) {
    std::string all;
    for (const auto& t : texts) all += t + "\n";
    return all;
}

// A valid configuration with one gimbal of each link type, every other key at its default.
json valid_config() {
    return json::parse(R"({
      "gimbals": [
        {"name": "main", "protocol": "orion",
         "link": {"type": "tcp", "host": "192.168.1.20", "port": 8747}},
        {"name": "nose", "protocol": "viewpro",
         "link": {"type": "serial", "device": "/dev/ttyUSB0", "baud": 115200}},
        {"name": "bench", "protocol": "orion", "link": {"type": "sim"}}
      ]
    })");
}

// Applies `edit` to a valid configuration and returns the problems of the result.
template <class Edit>
std::vector<std::string> problems_after(Edit edit) {
    json config = valid_config();
    edit(config);
    return problem_texts(parse_config(config.dump()));
}

const std::string baud_list =
    "1200, 1800, 2400, 4800, 9600, 19200, 38400, 57600, 115200, 230400, 460800, 500000, "
    "576000, 921600, 1000000, 1152000, 1500000, 2000000, 2500000, 3000000, 3500000, 4000000";

// Every object path of a JSON document, e.g. "", "gimbals[0]", "gimbals[0].link".
void object_paths(const json& value, const std::string& path, std::vector<std::string>& out) {
    if (value.is_object()) {
        out.push_back(path);
        for (const auto& [key, item] : value.items()) {
            object_paths(item, path.empty() ? key : path + "." + key, out);
        }
    } else if (value.is_array()) {
        for (std::size_t i = 0; i < value.size(); ++i) {
            object_paths(value[i], path + "[" + std::to_string(i) + "]", out);
        }
    }
}

json& at_path(json& root, const std::string& path) {
    // "gimbals[0].link" -> "/gimbals/0/link"
    std::string pointer;
    for (char c : path) {
        if (c == '.' || c == '[') {
            pointer += '/';
        } else if (c != ']') {
            pointer += c;
        }
    }
    if (!pointer.empty() && pointer.front() != '/') pointer.insert(pointer.begin(), '/');
    return root[json::json_pointer(pointer)];
}

// Leaf key paths with array indices dropped: "gimbals[].link.port".
void leaf_paths(const json& value, const std::string& path, std::vector<std::string>& out) {
    if (value.is_object()) {
        for (const auto& [key, item] : value.items()) {
            leaf_paths(item, path.empty() ? key : path + "." + key, out);
        }
    } else if (value.is_array() && !value.empty() && value[0].is_object()) {
        for (const auto& item : value) leaf_paths(item, path + "[]", out);
    } else {
        out.push_back(path);
    }
}

}  // namespace

TEST_CASE("the example configuration is valid and holds every default", "[config]") {
    const std::string path = source_dir + "/config/gimbald.json";
    const auto result = load_config_file(path);
    INFO(joined(problem_texts(result)));
    REQUIRE(result.ok());
    const Config& config = result.config;
    REQUIRE(config.gimbals.size() == 2);
    CHECK(config.gimbals[0].name == "main");
    CHECK(config.gimbals[1].protocol == Protocol::viewpro);
    REQUIRE(config.vehicle.has_value());

    // Serialising the parsed file gives back exactly the file: no key is lost or invented.
    CHECK(to_json(config) == read_json(path));

    // The same gimbals with only the required keys, and an empty vehicle section, give the
    // same configuration: every other value in the file is the default.
    json minimal = valid_config();
    minimal["gimbals"].erase(2);
    minimal["gimbals"][0]["video"] = {{"input", "udp://0.0.0.0:15004"}};  // its required key
    minimal["gimbals"][0]["video"]["tracking"] = json::object();          // every key has a default
    minimal["vehicle"] = json::object();
    minimal["mqtt"] = {{"station", "ground-1"}};  // the station default is the host name
    minimal["http"] = json::object();
    minimal["record"] = {{"dir", "/var/tmp"}};  // the one required key of `record`
    minimal["terrain"] = {{"files", {"/var/lib/gimbald/dem/*.tif"}}};  // and of `terrain`
    const auto defaults = parse_config(minimal.dump());
    REQUIRE(defaults.ok());
    CHECK(defaults.config == config);
}

TEST_CASE("the sim example configuration is valid", "[config]") {
    const auto result = load_config_file(source_dir + "/config/sim.json");
    INFO(joined(problem_texts(result)));
    REQUIRE(result.ok());
    REQUIRE(result.config.gimbals.size() == 1);
    const auto& gimbal = result.config.gimbals[0];
    CHECK(gimbal.protocol == Protocol::orion);
    const auto* tcp = std::get_if<TcpLink>(&gimbal.link);
    REQUIRE(tcp != nullptr);
    CHECK(tcp->host == "127.0.0.1");
    CHECK(tcp->port == 8747);
}

TEST_CASE("the packaged configuration is valid, has no gimbals and only defaults", "[config]") {
    // packaging/gimbald.json becomes the conffile /etc/gimbald/gimbald.json of the .deb.
    const auto result = load_config_file(source_dir + "/packaging/gimbald.json");
    INFO(joined(problem_texts(result)));
    REQUIRE(result.ok());
    CHECK(result.config.gimbals.empty());
    const auto defaults = parse_config(R"({"gimbals": []})");
    REQUIRE(defaults.ok());
    CHECK(result.config == defaults.config);
}

TEST_CASE("docs/configuration.md documents every key", "[config]") {
    const std::string docs = read_text(source_dir + "/docs/configuration.md");
    REQUIRE(!docs.empty());
    std::vector<std::string> paths;
    leaf_paths(read_json(source_dir + "/config/gimbald.json"), "", paths);
    // Keys the example cannot show at once: the other vehicle source.
    paths.push_back("vehicle.source.device");
    paths.push_back("vehicle.source.baud");
    for (const auto& path : paths) {
        INFO(path);
        CHECK(docs.find("`" + path + "`") != std::string::npos);
    }
}

TEST_CASE("defaults are applied to absent keys", "[config]") {
    const auto result = parse_config(valid_config().dump());
    INFO(joined(problem_texts(result)));
    REQUIRE(result.ok());
    const Config& c = result.config;

    const auto& tcp = std::get<TcpLink>(c.gimbals[0].link);
    CHECK(tcp.connect_timeout_s == 3.0);
    CHECK(tcp.reconnect_min_s == 0.2);
    CHECK(tcp.reconnect_max_s == 5.0);
    CHECK(tcp.silence_timeout_s == 3.0);
    CHECK(tcp.discover_address == "255.255.255.255");
    CHECK(tcp.discover_port == 8745);
    CHECK(tcp.discover_reply_port == 8746);
    CHECK_FALSE(tcp.discover());
    const auto orion = gimbal::config::read_checked<OrionConfig>(c.gimbals[0].protocol_config);
    CHECK(orion.feed_autopilot);
    CHECK_FALSE(orion.feed_gps);

    const auto& serial = std::get<SerialLink>(c.gimbals[1].link);
    CHECK(serial.device == "/dev/ttyUSB0");
    CHECK(serial.baud == 115200);
    CHECK(serial.reconnect_min_s == 0.2);
    CHECK(serial.reconnect_max_s == 5.0);
    const auto viewpro = gimbal::config::read_checked<ViewproConfig>(c.gimbals[1].protocol_config);
    CHECK(viewpro.output.osd == gimbal::viewpro::Osd::target);
    CHECK(viewpro.output.serial);
    CHECK_FALSE(viewpro.output.network);
    CHECK(viewpro.output.format == gimbal::viewpro::OutFormat::out3);
    CHECK(viewpro.feed == ViewproFeed::in2);
    CHECK(std::holds_alternative<SimLink>(c.gimbals[2].link));

    CHECK(c.command.bind.to_string() == "127.0.0.1");
    CHECK(c.command.port == 8760);
    REQUIRE(c.command.allow.size() == 2);
    CHECK(c.command.allow[0].to_string() == "127.0.0.0/8");
    CHECK(c.command.allow[1].to_string() == "::1/128");
    CHECK_FALSE(c.command.token.has_value());
    CHECK(c.command.max_subscribers == 64);
    CHECK_FALSE(c.laser.allow_fire);
    CHECK(c.laser.fire_timeout_s == 5.0);
    CHECK_FALSE(c.laser.allow_safety_bypass);
    CHECK_FALSE(c.stare.auto_ack);
    CHECK(c.telemetry.stale_after_s == 1.0);
    CHECK(c.log.level == gimbal::log::Level::info);
    CHECK(c.log.format == gimbal::log::Format::json);
    CHECK_FALSE(c.log.file.has_value());
    CHECK_FALSE(c.vehicle.has_value());
}

TEST_CASE("given values are read", "[config]") {
    json config = valid_config();
    config["gimbals"][0]["link"] = {{"type", "tcp"},
                                    {"host", "discover"},
                                    {"port", 8747},
                                    {"connect_timeout_s", 1.5},
                                    {"reconnect_min_s", 1},
                                    {"reconnect_max_s", 30},
                                    {"silence_timeout_s", 10},
                                    {"discover_address", "192.168.1.255"},
                                    {"discover_port", 9745},
                                    {"discover_reply_port", 9746}};
    config["gimbals"][0]["feed"] = {{"autopilot", false}, {"gps", true}};
    config["gimbals"][1]["viewpro"] = {
        {"output", {{"osd", "uav"}, {"serial", false}, {"network", true}, {"format", "out1"}}}};
    config["gimbals"][1]["feed"] = "mavlink";
    // Loopback: laser fire on another address would need signed commands (section 10).
    config["command"] = {{"bind", "::1"},
                         {"port", 9000},
                         {"allow", {"10.0.0.0/8"}},
                         {"token", "s3cret"},
                         {"max_subscribers", 5},
                         {"max_skew_s", 12},
                         {"rate_limit", {{"per_source_hz", 50}, {"burst", 60}}}};
    config["laser"] = {
        {"allow_fire", true}, {"fire_timeout_s", 0.5}, {"allow_safety_bypass", true}};
    config["stare"] = {{"auto_ack", true}};
    config["telemetry"] = {{"stale_after_s", 2.5}};
    config["log"] = {{"level", "debug"}, {"format", "text"}, {"file", "/var/log/gimbald/g.log"}};
    config["vehicle"] = {
        {"source", {{"type", "serial"}, {"device", "/dev/ttyACM0"}, {"baud", 57600}}},
        {"system_id", 7},
        {"timeout_s", 3}};

    const auto result = parse_config(config.dump());
    INFO(joined(problem_texts(result)));
    REQUIRE(result.ok());
    const Config& c = result.config;
    const auto& tcp = std::get<TcpLink>(c.gimbals[0].link);
    CHECK(tcp.discover());
    CHECK(tcp.connect_timeout_s == 1.5);
    CHECK(tcp.reconnect_min_s == 1.0);
    CHECK(tcp.reconnect_max_s == 30.0);
    CHECK(tcp.silence_timeout_s == 10.0);
    CHECK(tcp.discover_address == "192.168.1.255");
    CHECK(tcp.discover_port == 9745);
    CHECK(tcp.discover_reply_port == 9746);
    const auto orion = gimbal::config::read_checked<OrionConfig>(c.gimbals[0].protocol_config);
    CHECK_FALSE(orion.feed_autopilot);
    CHECK(orion.feed_gps);
    const auto viewpro = gimbal::config::read_checked<ViewproConfig>(c.gimbals[1].protocol_config);
    CHECK(viewpro.output == gimbal::viewpro::Mode{gimbal::viewpro::Osd::uav, true, false,
                                                  gimbal::viewpro::OutFormat::out1});
    CHECK(viewpro.feed == ViewproFeed::mavlink);
    CHECK(c.command.bind.to_string() == "::1");
    CHECK(c.command.max_skew_s == 12);
    CHECK(c.command.rate_limit == RateLimitConfig{50, 60});
    CHECK(c.command.port == 9000);
    CHECK(c.command.token == std::optional<std::string>("s3cret"));
    CHECK(c.command.max_subscribers == 5);
    CHECK(c.laser.allow_fire);
    CHECK(c.laser.fire_timeout_s == 0.5);
    CHECK(c.laser.allow_safety_bypass);
    CHECK(c.stare.auto_ack);
    CHECK(c.telemetry.stale_after_s == 2.5);
    CHECK(c.log.level == gimbal::log::Level::debug);
    CHECK(c.log.format == gimbal::log::Format::text);
    CHECK(c.log.file == std::optional<std::string>("/var/log/gimbald/g.log"));
    REQUIRE(c.vehicle.has_value());
    CHECK(c.vehicle->source ==
          std::variant<UdpSource, SerialSource>(SerialSource{"/dev/ttyACM0", 57600}));
    CHECK(c.vehicle->system_id == std::optional<std::uint8_t>(7));
    CHECK(c.vehicle->timeout_s == 3.0);

    // to_json is the inverse of parse_config (token shown on request only).
    CHECK(to_json(c)["command"]["token"] == "***");
    const auto again = parse_config(to_json(c, true).dump());
    REQUIRE(again.ok());
    CHECK(again.config == c);
}

TEST_CASE("each invalid value is reported with its path and message", "[config]") {
    struct Case {
        const char* what;
        std::function<void(json&)> edit;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {"baud not standard", [](json& c) { c["gimbals"][1]["link"]["baud"] = 115201; },
         "gimbals[1].link.baud: must be one of " + baud_list},
        {"baud as text", [](json& c) { c["gimbals"][1]["link"]["baud"] = "115200"; },
         "gimbals[1].link.baud: must be one of " + baud_list},
        {"laser timeout", [](json& c) { c["laser"]["fire_timeout_s"] = 0; },
         "laser.fire_timeout_s: must be between 0.1 and 3600"},
        {"laser timeout type", [](json& c) { c["laser"]["fire_timeout_s"] = "5"; },
         "laser.fire_timeout_s: must be a number between 0.1 and 3600"},
        {"duplicate name", [](json& c) { c["gimbals"][2]["name"] = "main"; },
         "gimbals[2].name: duplicate name \"main\" (also gimbals[0])"},
        {"bad CIDR",
         [](json& c) {
             c["command"]["allow"] = {"127.0.0.0/8", "::1/128", "10.0.0.0/33"};
         },
         "command.allow[2]: not a CIDR"},
        {"CIDR not a string",
         [](json& c) {
             c["command"]["allow"] = {"127.0.0.0/8", 10};
         },
         "command.allow[1]: not a CIDR"},
        {"empty allow", [](json& c) { c["command"]["allow"] = json::array(); },
         "command.allow: must be a non-empty array of CIDR blocks such as \"127.0.0.0/8\""},
        {"upper-case name", [](json& c) { c["gimbals"][0]["name"] = "Main"; },
         "gimbals[0].name: must match [a-z0-9_-]{1,32}"},
        {"long name", [](json& c) { c["gimbals"][0]["name"] = std::string(33, 'a'); },
         "gimbals[0].name: must match [a-z0-9_-]{1,32}"},
        {"empty name", [](json& c) { c["gimbals"][0]["name"] = ""; },
         "gimbals[0].name: must match [a-z0-9_-]{1,32}"},
        {"missing name", [](json& c) { c["gimbals"][0].erase("name"); },
         "gimbals[0].name: required"},
        {"protocol", [](json& c) { c["gimbals"][0]["protocol"] = "trillium"; },
         "gimbals[0].protocol: must be one of \"orion\", \"viewpro\", \"mavlink\", \"siyi\""},
        {"missing link", [](json& c) { c["gimbals"][0].erase("link"); },
         "gimbals[0].link: required"},
        {"link not an object", [](json& c) { c["gimbals"][0]["link"] = "tcp"; },
         "gimbals[0].link: must be an object"},
        {"link type", [](json& c) { c["gimbals"][0]["link"]["type"] = "ftp"; },
         "gimbals[0].link.type: must be one of \"tcp\", \"serial\", \"sim\", \"udp\""},
        {"missing host", [](json& c) { c["gimbals"][0]["link"].erase("host"); },
         "gimbals[0].link.host: required"},
        {"host with space", [](json& c) { c["gimbals"][0]["link"]["host"] = "my host"; },
         "gimbals[0].link.host: must be a host name, an IP address or \"discover\""},
        {"discover without a discovery",
         [](json& c) {
             c["gimbals"][1]["link"] = {{"type", "tcp"}, {"host", "discover"}, {"port", 2000}};
         },
         "gimbals[1].link.host: \"discover\" only for a protocol with broadcast discovery "
         "(\"orion\")"},
        {"missing port", [](json& c) { c["gimbals"][0]["link"].erase("port"); },
         "gimbals[0].link.port: required"},
        {"port zero", [](json& c) { c["gimbals"][0]["link"]["port"] = 0; },
         "gimbals[0].link.port: must be between 1 and 65535"},
        {"port too big", [](json& c) { c["gimbals"][0]["link"]["port"] = 65536; },
         "gimbals[0].link.port: must be between 1 and 65535"},
        {"port negative", [](json& c) { c["gimbals"][0]["link"]["port"] = -1; },
         "gimbals[0].link.port: must be between 1 and 65535"},
        {"port huge", [](json& c) { c["gimbals"][0]["link"]["port"] = 18446744073709551615ull; },
         "gimbals[0].link.port: must be between 1 and 65535"},
        {"port fraction", [](json& c) { c["gimbals"][0]["link"]["port"] = 8747.5; },
         "gimbals[0].link.port: must be an integer between 1 and 65535"},
        {"port text", [](json& c) { c["gimbals"][0]["link"]["port"] = "8747"; },
         "gimbals[0].link.port: must be an integer between 1 and 65535"},
        {"connect timeout", [](json& c) { c["gimbals"][0]["link"]["connect_timeout_s"] = 0; },
         "gimbals[0].link.connect_timeout_s: must be between 0.1 and 60"},
        {"reconnect order",
         [](json& c) {
             c["gimbals"][0]["link"]["reconnect_min_s"] = 2;
             c["gimbals"][0]["link"]["reconnect_max_s"] = 1;
         },
         "gimbals[0].link.reconnect_max_s: must not be less than reconnect_min_s (2)"},
        {"reconnect max", [](json& c) { c["gimbals"][1]["link"]["reconnect_max_s"] = 4000; },
         "gimbals[1].link.reconnect_max_s: must be between 0.1 and 3600"},
        {"silence timeout", [](json& c) { c["gimbals"][0]["link"]["silence_timeout_s"] = 0; },
         "gimbals[0].link.silence_timeout_s: must be between 0.1 and 3600"},
        {"discover address v6",
         [](json& c) { c["gimbals"][0]["link"]["discover_address"] = "ff02::1"; },
         "gimbals[0].link.discover_address: must be an IPv4 address"},
        {"discover address text",
         [](json& c) { c["gimbals"][0]["link"]["discover_address"] = "all"; },
         "gimbals[0].link.discover_address: must be an IPv4 or IPv6 address"},
        {"discover port", [](json& c) { c["gimbals"][0]["link"]["discover_port"] = 0; },
         "gimbals[0].link.discover_port: must be between 1 and 65535"},
        {"relative device", [](json& c) { c["gimbals"][1]["link"]["device"] = "ttyUSB0"; },
         "gimbals[1].link.device: must be an absolute path such as /dev/ttyUSB0"},
        {"missing baud", [](json& c) { c["gimbals"][1]["link"].erase("baud"); },
         "gimbals[1].link.baud: required"},
        {"shared device",
         [](json& c) {
             c["gimbals"][2]["link"] = {
                 {"type", "serial"}, {"device", "/dev/ttyUSB0"}, {"baud", 9600}};
         },
         "gimbals[2].link.device: \"/dev/ttyUSB0\" is already used by gimbals[1]"},
        {"viewpro section on orion", [](json& c) { c["gimbals"][0]["viewpro"] = json::object(); },
         "gimbals[0].viewpro: only for protocol \"viewpro\""},
        {"viewpro osd", [](json& c) { c["gimbals"][1]["viewpro"]["output"]["osd"] = "gimbal"; },
         "gimbals[1].viewpro.output.osd: must be one of \"target\", \"uav\""},
        {"viewpro format", [](json& c) { c["gimbals"][1]["viewpro"]["output"]["format"] = "out5"; },
         "gimbals[1].viewpro.output.format: must be one of \"out1\", \"out2\", \"out3\", \"out4\""},
        {"viewpro serial", [](json& c) { c["gimbals"][1]["viewpro"]["output"]["serial"] = 1; },
         "gimbals[1].viewpro.output.serial: must be true or false"},
        {"viewpro output type", [](json& c) { c["gimbals"][1]["viewpro"]["output"] = "out3"; },
         "gimbals[1].viewpro.output: must be an object"},
        {"viewpro feed", [](json& c) { c["gimbals"][1]["feed"] = "in3"; },
         "gimbals[1].feed: must be one of \"in2\", \"in1\", \"mavlink\""},
        {"orion feed", [](json& c) { c["gimbals"][0]["feed"] = "in2"; },
         "gimbals[0].feed: must be an object"},
        {"orion feed gps",
         [](json& c) {
             c["gimbals"][0]["feed"] = {{"gps", "yes"}};
         },
         "gimbals[0].feed.gps: must be true or false"},
        {"gimbal not an object", [](json& c) { c["gimbals"][1] = "nose"; },
         "gimbals[1]: must be an object"},
        {"no gimbals", [](json& c) { c.erase("gimbals"); }, "gimbals: required"},
        {"33 gimbals",
         [](json& c) {
             json gimbals = json::array();
             for (int i = 0; i < 33; ++i) {
                 gimbals.push_back({{"name", "g" + std::to_string(i)},
                                    {"protocol", "orion"},
                                    {"link", {{"type", "sim"}}}});
             }
             c["gimbals"] = gimbals;
         },
         "gimbals: must list 0 to 32 gimbals"},
        {"gimbals not an array", [](json& c) { c["gimbals"] = json::object(); },
         "gimbals: must be an array of gimbals"},
        {"bind", [](json& c) { c["command"]["bind"] = "localhost"; },
         "command.bind: must be an IPv4 or IPv6 address"},
        {"command port", [](json& c) { c["command"]["port"] = 70000; },
         "command.port: must be between 1 and 65535"},
        {"empty token", [](json& c) { c["command"]["token"] = ""; },
         "command.token: must be null or a string of 1 to 256 characters"},
        {"token number", [](json& c) { c["command"]["token"] = 1234; },
         "command.token: must be null or a string of 1 to 256 characters"},
        {"max subscribers", [](json& c) { c["command"]["max_subscribers"] = 0; },
         "command.max_subscribers: must be between 1 and 1024"},
        {"allow fire", [](json& c) { c["laser"]["allow_fire"] = "false"; },
         "laser.allow_fire: must be true or false"},
        {"auto ack", [](json& c) { c["stare"]["auto_ack"] = nullptr; },
         "stare.auto_ack: must be true or false"},
        {"stale", [](json& c) { c["telemetry"]["stale_after_s"] = 100; },
         "telemetry.stale_after_s: must be between 0.1 and 60"},
        {"log level", [](json& c) { c["log"]["level"] = "verbose"; },
         "log.level: must be one of \"trace\", \"debug\", \"info\", \"warn\", \"error\""},
        {"log format", [](json& c) { c["log"]["format"] = "xml"; },
         "log.format: must be one of \"json\", \"text\""},
        {"log file", [](json& c) { c["log"]["file"] = 3; },
         "log.file: must be null or a file path"},
        {"section not an object", [](json& c) { c["laser"] = true; }, "laser: must be an object"},
        {"vehicle source type",
         [](json& c) {
             c["vehicle"]["source"] = {{"type", "tcp"}};
         },
         "vehicle.source.type: must be one of \"udp\", \"serial\""},
        {"vehicle source without type",
         [](json& c) {
             c["vehicle"]["source"] = {{"port", 1}};
         },
         "vehicle.source.type: required"},
        {"vehicle udp port",
         [](json& c) {
             c["vehicle"]["source"] = {{"type", "udp"}, {"port", 0}};
         },
         "vehicle.source.port: must be between 1 and 65535"},
        {"vehicle serial baud",
         [](json& c) {
             c["vehicle"]["source"] = {{"type", "serial"}, {"device", "/dev/ttyS1"}, {"baud", 100}};
         },
         "vehicle.source.baud: must be one of " + baud_list},
        {"vehicle serial shared",
         [](json& c) {
             c["vehicle"]["source"] = {
                 {"type", "serial"}, {"device", "/dev/ttyUSB0"}, {"baud", 57600}};
         },
         "vehicle.source.device: \"/dev/ttyUSB0\" is already used by gimbals[1]"},
        {"system id zero", [](json& c) { c["vehicle"]["system_id"] = 0; },
         "vehicle.system_id: must be between 1 and 255"},
        {"system id big", [](json& c) { c["vehicle"]["system_id"] = 256; },
         "vehicle.system_id: must be between 1 and 255"},
        {"vehicle timeout", [](json& c) { c["vehicle"]["timeout_s"] = 0.01; },
         "vehicle.timeout_s: must be between 0.1 and 60"},
    };
    for (const auto& c : cases) {
        INFO(c.what);
        const auto problems = problems_after(c.edit);
        INFO(joined(problems));
        // Exactly the one expected problem: nothing missed, nothing reported twice.
        REQUIRE(problems.size() == 1);
        CHECK(problems[0] == c.expected);
    }
}

TEST_CASE("every problem is reported, not just the first", "[config]") {
    const auto problems = problems_after([](json& c) {
        c["gimbals"][0]["name"] = "Main";
        c["gimbals"][1]["link"]["baud"] = 1;
        c["command"]["allow"] = {"x", "127.0.0.1/8", "y"};
        c["laser"]["fire_timeout_s"] = 1e9;
        c["log"]["colour"] = true;
    });
    CHECK(problems == std::vector<std::string>{
                          "gimbals[0].name: must match [a-z0-9_-]{1,32}",
                          "gimbals[1].link.baud: must be one of " + baud_list,
                          "command.allow[0]: not a CIDR",
                          "command.allow[2]: not a CIDR",
                          "laser.fire_timeout_s: must be between 0.1 and 3600",
                          "log.colour: unknown key",
                      });
}

TEST_CASE("unknown keys are rejected in every object", "[config]") {
    json full = read_json(source_dir + "/config/gimbald.json");
    std::vector<std::string> paths;
    object_paths(full, "", paths);
    REQUIRE(paths.size() >= 15);
    for (const auto& path : paths) {
        json config = full;
        at_path(config, path)["zzz_unknown"] = 1;
        const auto problems = problem_texts(parse_config(config.dump()));
        INFO("object: " << (path.empty() ? "(top level)" : path));
        REQUIRE(problems.size() == 1);
        CHECK(problems[0] == (path.empty() ? "" : path + ".") + "zzz_unknown: unknown key");
    }

    // Keys of another link type are unknown too, and typos get a suggestion.
    CHECK(problems_after([](json& c) { c["gimbals"][0]["link"]["baud"] = 9600; }) ==
          std::vector<std::string>{"gimbals[0].link.baud: unknown key"});
    CHECK(problems_after([](json& c) { c["gimbals"][2]["link"]["host"] = "x"; }) ==
          std::vector<std::string>{"gimbals[2].link.host: unknown key"});
    CHECK(problems_after([](json& c) { c["laser"]["allow_fir"] = true; }) ==
          std::vector<std::string>{"laser.allow_fir: unknown key (did you mean \"allow_fire\"?)"});
    CHECK(problems_after([](json& c) { c["gimbals"][1]["link"]["buad"] = 9600; }) ==
          std::vector<std::string>{"gimbals[1].link.buad: unknown key (did you mean \"baud\"?)"});
}

TEST_CASE("gimbals[].video: read with its defaults, every problem named", "[config][video]") {
    const auto read = parse_config(R"({"gimbals": [{"name": "a", "protocol": "orion",
        "link": {"type": "sim"}, "video": {"input": "rtsp://10.0.0.5/live?transport=tcp"}}]})");
    INFO(joined(problem_texts(read)));
    REQUIRE(read.ok());
    REQUIRE(read.config.gimbals[0].video.has_value());
    const auto& video = *read.config.gimbals[0].video;
    CHECK(video.input == "rtsp://10.0.0.5/live?transport=tcp");
    CHECK(video.klv == gimbald::video::KlvMode::automatic);
    CHECK(video.klv_rate_hz == 10);
    CHECK(video.outputs.empty());
    CHECK_FALSE(video.mission_id.has_value());

    auto problems = problems_after([](json& c) {
        c["gimbals"][0]["video"] = {
            {"input", "udp://0.0.0.0:15004"},
            {"klv", "maybe"},
            {"klv_rate_hz", 0},
            {"outputs",
             {"udp://127.0.0.1:15004", "rtsp://10.0.0.5/x", "udp://gs.local:5000",
              "klv-udp://127.0.0.1:15011", "klv-udp://127.0.0.1:15011", "udp://0.0.0.0:5000"}},
            {"mission_id", ""},
            {"outptus", 1}};
        c["gimbals"][1]["video"] = {{"input", "klv-udp://127.0.0.1:15011"}};
        c["gimbals"][2]["video"] = {{"klv", "off"}};
    });
    std::sort(problems.begin(), problems.end());
    std::vector<std::string> expected = {
        "gimbals[0].video.klv: must be one of \"auto\", \"parse\", \"generate\", \"off\"",
        "gimbals[0].video.klv_rate_hz: must be a number between 0.1 and 60",
        "gimbals[0].video.outputs[0]: sends to the input's own port: the relay would feed itself",
        "gimbals[0].video.outputs[1]: an output is udp:// (MPEG-TS) or klv-udp:// (KLV only), "
        "not rtsp://",
        "gimbals[0].video.outputs[2]: \"gs.local\" is not a numeric IP address (names are not "
        "resolved for video)",
        "gimbals[0].video.outputs[4]: listed twice",
        "gimbals[0].video.outputs[5]: an output needs a destination address, not 0.0.0.0",
        "gimbals[0].video.mission_id: must be 1 to 127 bytes (ST 0601 tag 3)",
        "gimbals[0].video.outptus: unknown key (did you mean \"outputs\"?)",
        "gimbals[1].video.input: an input is udp:// (MPEG-TS) or rtsp://, not klv-udp://",
        "gimbals[2].video.input: required: udp://HOST:PORT or rtsp://HOST/PATH",
    };
    std::sort(expected.begin(), expected.end());
    CHECK(problems == expected);
}

TEST_CASE("gimbals[].video.tracking: the contract's defaults, every refusal named",
          "[config][video][track]") {
    const auto off = parse_config(R"({"gimbals": [{"name": "a", "protocol": "orion",
        "link": {"type": "sim"}, "video": {"input": "udp://0.0.0.0:15004"}}]})");
    REQUIRE(off.ok());
    CHECK_FALSE(off.config.gimbals[0].video->tracking.has_value());

    const auto read = parse_config(R"({"gimbals": [{"name": "a", "protocol": "orion",
        "link": {"type": "sim"}, "video": {"input": "udp://0.0.0.0:15004", "tracking": {}}}]})");
    INFO(joined(problem_texts(read)));
    REQUIRE(read.ok());
    REQUIRE(read.config.gimbals[0].video->tracking.has_value());
    const auto& tracking = *read.config.gimbals[0].video->tracking;
    CHECK(tracking.tracker == gimbald::video::TrackerKind::csrt);
    CHECK(tracking.width == 640);
    CHECK(tracking.lost_after_s == 1.0);
    CHECK(tracking.reacquire_s == 10);
    CHECK(tracking.steer);
    // Written back whole, read back the same.
    const json written = gimbal::config::write(*read.config.gimbals[0].video);
    CHECK(written["tracking"] == json::parse(R"({"tracker": "csrt", "width": 640,
        "lost_after_s": 1.0, "reacquire_s": 10, "steer": true})"));

    auto problems = problems_after([](json& c) {
        c["gimbals"][0]["video"] = {{"input", "udp://0.0.0.0:15004"},
                                    {"tracking",
                                     {{"tracker", "mosse"},
                                      {"width", 32},
                                      {"lost_after_s", 0},
                                      {"reacquire_s", -1},
                                      {"steer", "yes"},
                                      {"stear", true}}}};
        c["gimbals"][1]["video"] = {{"input", "udp://0.0.0.0:15005"}, {"tracking", "kcf"}};
        c["gimbals"][2]["video"] = {{"input", "udp://0.0.0.0:15006"},
                                    {"tracking", {{"width", 640.5}}}};
    });
    std::sort(problems.begin(), problems.end());
    std::vector<std::string> expected = {
        "gimbals[0].video.tracking.lost_after_s: must be between 0.1 and 60",
        "gimbals[0].video.tracking.reacquire_s: must be between 0 and 3600",
        "gimbals[0].video.tracking.stear: unknown key (did you mean \"steer\"?)",
        "gimbals[0].video.tracking.steer: must be true or false",
        "gimbals[0].video.tracking.tracker: must be one of \"csrt\", \"kcf\"",
        "gimbals[0].video.tracking.width: must be between 64 and 3840",
        "gimbals[1].video.tracking: must be an object",
        "gimbals[2].video.tracking.width: must be an integer between 64 and 3840",
    };
    std::sort(expected.begin(), expected.end());
    CHECK(problems == expected);
}

TEST_CASE("duplicate keys are rejected with their path", "[config]") {
    const auto result = parse_config(R"({
      "gimbals": [
        {"name": "a", "protocol": "orion", "link": {"type": "sim"}},
        {"name": "b", "protocol": "orion", "link": {"type": "tcp", "host": "h", "port": 1, "port": 2}}
      ],
      "laser": {"allow_fire": false, "allow_fire": true}
    })");
    CHECK(problem_texts(result) == std::vector<std::string>{"gimbals[1].link.port: duplicate key",
                                                            "laser.allow_fire: duplicate key"});
}

TEST_CASE("JSON syntax errors give line and column", "[config]") {
    const auto result = parse_config("{\n  \"gimbals\": [\n    {\"name\": \"a\",}\n  ]\n}\n");
    REQUIRE(result.problems.size() == 1);
    CHECK(result.problems[0].path.empty());
    CHECK_THAT(result.problems[0].message, Catch::StartsWith("line 3, column 18: syntax error"));

    const auto truncated = parse_config("{\"gimbals\": [");
    REQUIRE(truncated.problems.size() == 1);
    CHECK_THAT(truncated.problems[0].message, Catch::StartsWith("line 1, column 14: "));

    CHECK(problem_texts(parse_config("[1, 2]")) ==
          std::vector<std::string>{"the configuration must be a JSON object"});
    CHECK(problem_texts(parse_config("")).size() == 1);
    // A number beyond a double is one problem, not an exception (found by fuzz_config).
    CHECK(problem_texts(parse_config("{\"telemetry\": {\"stale_after_s\": 1e5200}}")) ==
          std::vector<std::string>{"number overflow parsing '1e5200'"});
}

TEST_CASE("an unreadable file is one problem", "[config]") {
    const auto result = load_config_file("/nonexistent/gimbald.json");
    CHECK(problem_texts(result) ==
          std::vector<std::string>{
              "cannot read /nonexistent/gimbald.json: No such file or directory"});
}

TEST_CASE("a configuration is a regular file of at most 1 MiB with no NUL", "[config]") {
    // Contract section 14 (v4): /dev/zero aborted with bad_alloc at 2.1 GB, a FIFO hung,
    // text after a NUL was accepted, a 5 MB unclosed array took 1.1 GB.
    CHECK(
        problem_texts(load_config_file("/dev/zero")) ==
        std::vector<std::string>{"cannot read /dev/zero: not a regular file (a character device)"});
    CHECK(problem_texts(load_config_file("/tmp")) ==
          std::vector<std::string>{"cannot read /tmp: not a regular file (a directory)"});
    const std::string fifo =
        (std::filesystem::temp_directory_path() / ("gimbald-config-" + std::to_string(::getpid())))
            .string();
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // Were the FIFO waited on, this writer would end the wait after 2 s (and the text read
    // would be empty): the check below tells the two apart without hanging.
    std::thread unblock([&fifo] {
        std::this_thread::sleep_for(std::chrono::seconds(2));
        const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
    });
    CHECK(problem_texts(load_config_file(fifo)) ==
          std::vector<std::string>{"cannot read " + fifo + ": not a regular file (a FIFO)"});
    unblock.join();
    std::filesystem::remove(fifo);

    using namespace std::string_literals;
    CHECK(problem_texts(parse_config("{\"gimbals\": []}\n\0{\"laser\": {}}"s)) ==
          std::vector<std::string>{"line 2, column 1: a NUL byte: not a JSON text file"});
    CHECK(problem_texts(parse_config("{\"gimbals\": [" + std::string(5'000'000, '['))) ==
          std::vector<std::string>{"larger than 1 MiB: not a gimbald configuration"});
    CHECK(problem_texts(parse_config("{\"gimbals\": [" + std::string(40, '['))) ==
          std::vector<std::string>{"JSON nested deeper than 32 levels"});
    std::string padded = "{\"gimbals\": []}";
    padded.resize(max_config_bytes, ' ');
    CHECK(parse_config(padded).ok());
}

TEST_CASE("under --sim the file's gimbals are not read", "[config]") {
    json config = valid_config();
    config["gimbals"][0]["link"]["baud"] = "nonsense";
    config["laser"]["fire_timeout_s"] = 2;
    CHECK_FALSE(parse_config(config.dump()).ok());

    const auto result = parse_config(config.dump(), GimbalsSection::ignored);
    REQUIRE(result.ok());
    CHECK(result.config.gimbals.empty());
    CHECK(result.config.laser.fire_timeout_s == 2.0);

    // The other sections are still checked, and the key may be absent altogether.
    config.erase("gimbals");
    config["laser"]["fire_timeout_s"] = -1;
    CHECK(problem_texts(parse_config(config.dump(), GimbalsSection::ignored)) ==
          std::vector<std::string>{"laser.fire_timeout_s: must be between 0.1 and 3600"});
    CHECK(parse_config("{}", GimbalsSection::ignored).ok());
}

TEST_CASE("the --sim gimbals", "[config]") {
    const auto alone = sim_gimbals({});
    REQUIRE(alone.size() == 1);
    CHECK(alone[0].name == "sim");
    CHECK(alone[0].protocol == Protocol::orion);
    CHECK(std::holds_alternative<SimLink>(alone[0].link));

    const std::vector<Protocol> both = {Protocol::orion, Protocol::viewpro};
    const auto two = sim_gimbals(both);
    REQUIRE(two.size() == 2);
    CHECK(two[0].name == "sim-orion");
    CHECK(two[0].protocol == Protocol::orion);
    CHECK(two[1].name == "sim-viewpro");
    CHECK(two[1].protocol == Protocol::viewpro);
    CHECK(std::holds_alternative<SimLink>(two[1].link));

    // What they produce is itself a valid configuration.
    Config config;
    config.gimbals = two;
    CHECK(parse_config(to_json(config).dump()).ok());
}

TEST_CASE("CIDR blocks", "[config]") {
    using boost::asio::ip::make_address;
    const auto loopback = Cidr::parse("127.0.0.0/8");
    REQUIRE(loopback);
    CHECK(loopback->contains(make_address("127.0.0.1")));
    CHECK(loopback->contains(make_address("127.255.255.254")));
    CHECK_FALSE(loopback->contains(make_address("128.0.0.1")));
    CHECK_FALSE(loopback->contains(make_address("::1")));
    // Dual-stack sockets report IPv4 peers as IPv4-mapped IPv6 addresses.
    CHECK(loopback->contains(make_address("::ffff:127.0.0.1")));
    CHECK_FALSE(loopback->contains(make_address("::ffff:10.0.0.1")));

    const auto host = Cidr::parse("192.168.1.77/24");
    REQUIRE(host);
    CHECK(host->to_string() == "192.168.1.0/24");
    CHECK(host->contains(make_address("192.168.1.1")));
    CHECK_FALSE(host->contains(make_address("192.168.2.1")));

    const auto odd = Cidr::parse("10.0.0.0/9");
    REQUIRE(odd);
    CHECK(odd->contains(make_address("10.127.0.1")));
    CHECK_FALSE(odd->contains(make_address("10.128.0.1")));

    const auto link_local = Cidr::parse("fe80::/10");
    REQUIRE(link_local);
    CHECK(link_local->contains(make_address("fe80::1")));
    CHECK(link_local->contains(make_address("febf::1")));
    CHECK_FALSE(link_local->contains(make_address("fec0::1")));

    const auto single = Cidr::parse("10.1.2.3");
    REQUIRE(single);
    CHECK(single->to_string() == "10.1.2.3/32");
    CHECK_FALSE(single->contains(make_address("10.1.2.4")));

    const auto everything = Cidr::parse("0.0.0.0/0");
    REQUIRE(everything);
    CHECK(everything->contains(make_address("8.8.8.8")));
    CHECK_FALSE(everything->contains(make_address("2001:db8::1")));

    for (const char* bad : {"", "/8", "10.0.0.0/", "10.0.0.0/33", "::/129", "10.0.0.0/-1",
                            "10.0.0.0/8x", "10.0.0/8", "host/8", "10.0.0.0/0008"}) {
        INFO(bad);
        CHECK_FALSE(Cidr::parse(bad));
    }

    CommandConfig command;
    CHECK(command.allowed(make_address("127.0.0.1")));
    CHECK(command.allowed(make_address("::1")));
    CHECK_FALSE(command.allowed(make_address("::2")));
    CHECK_FALSE(command.allowed(make_address("192.168.1.5")));
}

TEST_CASE("links describe themselves", "[config]") {
    auto tcp = [](std::string host) {
        TcpLink link;
        link.host = std::move(host);
        link.port = 8747;
        return link;
    };
    CHECK(describe(tcp("192.168.1.20")) == "192.168.1.20:8747");
    CHECK(describe(tcp("fe80::1")) == "[fe80::1]:8747");
    CHECK(describe(tcp("discover")) == "discover via 255.255.255.255:8745");
    SerialLink serial;
    serial.device = "/dev/ttyUSB0";
    serial.baud = 115200;
    CHECK(describe(serial) == "/dev/ttyUSB0@115200");
    CHECK(describe(SimLink{}) == "sim");
    CHECK(link_type(SerialLink{}) == "serial");
}

TEST_CASE("a MAVLink gimbal device: its mavlink section and a UDP link", "[config]") {
    json config = valid_config();
    config["gimbals"].push_back(json::parse(R"({
        "name": "cam", "protocol": "mavlink",
        "link": {"type": "udp", "host": "192.168.1.30", "port": 14570, "local_port": null},
        "mavlink": {"hfov_deg": 45, "device_component_id": 155}})"));
    const auto result = parse_config(config.dump());
    INFO(joined(problem_texts(result)));
    REQUIRE(result.ok());
    const auto& g = result.config.gimbals.back();
    CHECK(g.protocol == Protocol::mavlink);
    const auto device = gimbal::config::read_checked<MavlinkDeviceConfig>(g.protocol_config);
    CHECK(device.hfov_deg == 45);
    CHECK(device.vfov_deg == 34);
    CHECK(device.device_component_id == 155);
    CHECK_FALSE(device.geoid_undulation_m);  // null: EGM96 where the aircraft flies
    const auto& udp = std::get<UdpLink>(g.link);
    CHECK(udp.host == "192.168.1.30");
    CHECK(udp.port == 14570);
    CHECK_FALSE(udp.local_port);
    CHECK(describe(g.link) == "udp 192.168.1.30:14570");
    CHECK(link_type(g.link) == "udp");
    // Written back with every default, and read again to the same.
    const json written = to_json(result.config);
    const json& cam = written["gimbals"][3];
    CHECK(cam["mavlink"]["system_id"] == 1);
    CHECK(cam["mavlink"]["geoid_undulation_m"].is_null());
    CHECK(cam["link"]["local_port"].is_null());
    CHECK(cam.find("feed") == cam.end());
    const auto again = parse_config(written.dump());
    REQUIRE(again.ok());
    CHECK(again.config == result.config);

    CHECK(problems_after([](json& c) { c["gimbals"][0]["mavlink"] = json::object(); }) ==
          std::vector<std::string>{"gimbals[0].mavlink: only for protocol \"mavlink\""});
    const auto bad = [&](const std::function<void(json&)>& edit) {
        json c = config;
        edit(c["gimbals"][3]);
        return problem_texts(parse_config(c.dump()));
    };
    CHECK(bad([](json& x) { x["link"]["local_port"] = 0; }) ==
          std::vector<std::string>{"gimbals[3].link.local_port: must be between 1 and 65535"});
    CHECK(bad([](json& x) { x["mavlink"]["hfov_deg"] = 180; }) ==
          std::vector<std::string>{"gimbals[3].mavlink.hfov_deg: must be between 0.1 and 179.9"});
    CHECK(bad([](json& x) { x["mavlink"]["geoid_undulation_m"] = nullptr; }).empty());
    CHECK(bad([](json& x) { x["mavlink"]["geoid_undulation_m"] = "egm96"; }) ==
          std::vector<std::string>{
              "gimbals[3].mavlink.geoid_undulation_m: must be a number between -200 and 200"});
    json fixed = config;
    fixed["gimbals"][3]["mavlink"]["geoid_undulation_m"] = -19.5;
    const auto overridden = parse_config(fixed.dump());
    REQUIRE(overridden.ok());
    CHECK(gimbal::config::read_checked<MavlinkDeviceConfig>(
              overridden.config.gimbals.back().protocol_config)
              .geoid_undulation_m == -19.5);
    CHECK(to_json(overridden.config)["gimbals"][3]["mavlink"]["geoid_undulation_m"] == -19.5);
    CHECK(bad([](json& x) { x["feed"] = "in2"; }) ==
          std::vector<std::string>{"gimbals[3].feed: unknown key"});
}

TEST_CASE("standard baud rates", "[config]") {
    const auto rates = standard_baud_rates();
    CHECK(rates.front() == 1200);
    CHECK(rates.back() == 4000000);
    CHECK(std::is_sorted(rates.begin(), rates.end()));
    for (std::uint32_t rate : {1200u, 9600u, 115200u, 921600u, 4000000u}) {
        INFO(rate);
        CHECK(problems_after([rate](json& c) { c["gimbals"][1]["link"]["baud"] = rate; }).empty());
    }
    for (std::uint32_t rate : {0u, 300u, 600u, 115201u, 4000001u}) {
        INFO(rate);
        CHECK(problems_after([rate](json& c) { c["gimbals"][1]["link"]["baud"] = rate; }).size() ==
              1);
    }
}

namespace {

// A secret file in a fresh temporary directory, with the given text and mode.
std::string secret_file(const std::string& name, const std::string& text, unsigned mode) {
    static const std::string dir = [] {
        char pattern[] = "/tmp/gimbald-config-test-XXXXXX";
        return std::string(::mkdtemp(pattern));
    }();
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    ::chmod(path.c_str(), mode);
    return path;
}

const std::string hex_secret = std::string(64, 'a') + "\n";

json with_key(const std::string& file, json roles = {"observe", "control"}) {
    json config = valid_config();
    config["command"] = {{"auth", "signed"},
                         {"keys", {{{"id", "ops"}, {"secret_file", file}, {"roles", roles}}}}};
    return config;
}

}  // namespace

TEST_CASE("signed commands: keys are read with their secrets", "[config][auth]") {
    const auto file = secret_file("good.key", hex_secret, 0600);
    const auto result = parse_config(with_key(file, {"observe", "control", "laser"}).dump());
    INFO(joined(problem_texts(result)));
    REQUIRE(result.ok());
    const auto& command = result.config.command;
    CHECK(command.auth == AuthMode::signed_requests);
    REQUIRE(command.keys.size() == 1);
    CHECK(command.keys[0].secret == std::vector<std::uint8_t>(32, 0xaa));
    CHECK(command.keys[0].roles == std::vector<std::string>{"observe", "control", "laser"});
    // The secret never appears in the configuration dump.
    const auto dumped = to_json(result.config).dump();
    CHECK(dumped.find("aaaaaaaa") == std::string::npos);
    CHECK(dumped.find(file) != std::string::npos);
}

TEST_CASE("signed commands: bad keys stop the start with path and reason", "[config][auth]") {
    const auto open = secret_file("open.key", hex_secret, 0644);
    const auto short_key = secret_file("short.key", std::string(40, 'a'), 0600);
    const auto not_hex = secret_file("nothex.key", std::string(64, 'x'), 0400);
    auto problems = [](const json& config) {
        return joined(problem_texts(parse_config(config.dump())));
    };
    CHECK_THAT(problems(with_key(open)),
               Catch::Contains("command.keys[0].secret_file: " + open +
                               ": readable by group or others (mode 0644)"));
    CHECK_THAT(problems(with_key(short_key)), Catch::Contains(short_key + ": too short"));
    CHECK_THAT(problems(with_key(not_hex)), Catch::Contains(not_hex + ": not hex"));
    CHECK_THAT(problems(with_key("/nonexistent/ops.key")),
               Catch::Contains("/nonexistent/ops.key: missing"));
    const auto good = secret_file("good2.key", hex_secret, 0400);
    CHECK_THAT(problems(with_key(good, {"observe", "root"})),
               Catch::Contains("command.keys[0].roles[1]"));
    CHECK_THAT(problems(with_key(good, json::array())), Catch::Contains("command.keys[0].roles"));

    json duplicate = with_key(good);
    duplicate["command"]["keys"].push_back(duplicate["command"]["keys"][0]);
    CHECK_THAT(problems(duplicate), Catch::Contains("duplicate key id"));

    json both = with_key(good);
    both["command"]["token"] = "s3cret";
    CHECK_THAT(problems(both), Catch::Contains("may not both be set"));

    json no_keys = valid_config();
    no_keys["command"] = {{"auth", "signed"}};
    CHECK_THAT(problems(no_keys), Catch::Contains("command.auth"));
    json typo = valid_config();
    typo["command"] = {{"auth", "hmac"}};
    CHECK_THAT(problems(typo), Catch::Contains("command.auth: must be one of"));
    json rate = valid_config();
    rate["command"] = {{"rate_limit", {{"per_source_hz", 0}, {"brust", 5}}}};
    const auto rate_problems = problems(rate);
    CHECK_THAT(rate_problems, Catch::Contains("command.rate_limit.per_source_hz"));
    CHECK_THAT(rate_problems, Catch::Contains("command.rate_limit.brust: unknown key"));
}

TEST_CASE("laser fire on a non-loopback socket needs signed commands", "[config][auth]") {
    json config = valid_config();
    config["laser"] = {{"allow_fire", true}};
    config["command"] = {{"bind", "0.0.0.0"}};
    CHECK_THAT(joined(problem_texts(parse_config(config.dump()))),
               Catch::Contains("command.auth: laser.allow_fire is true and command.bind"));
    config["command"]["bind"] = "127.0.0.1";
    CHECK(parse_config(config.dump()).ok());
    config["command"] = with_key(secret_file("fire.key", hex_secret, 0600))["command"];
    config["command"]["bind"] = "0.0.0.0";
    CHECK(parse_config(config.dump()).ok());
}

TEST_CASE("record: dir must be an existing writable directory, sizes in range", "[config]") {
    const auto with_record = [](json record) {
        return problems_after([&](json& c) { c["record"] = record; });
    };
    CHECK(with_record({{"dir", "/var/tmp"}}).empty());
    const auto fractions = parse_config(
        R"({"gimbals": [], "record": {"dir": "/var/tmp", "max_file_mb": 0.05, "max_total_mb": 0.2}})",
        GimbalsSection::ignored);
    REQUIRE(fractions.ok());
    REQUIRE(fractions.config.record.has_value());
    CHECK(fractions.config.record->max_file_mb == 0.05);
    CHECK(fractions.config.record->max_total_mb == 0.2);
    CHECK(with_record(json::object()) == std::vector<std::string>{"record.dir: required"});
    CHECK(with_record({{"dir", "/nonexistent/rec"}}) ==
          std::vector<std::string>{"record.dir: /nonexistent/rec: No such file or directory"});
    CHECK(with_record({{"dir", "/etc/passwd"}}) ==
          std::vector<std::string>{"record.dir: /etc/passwd: not a directory"});
    CHECK(with_record({{"dir", "/var/tmp"}, {"max_file_mb", 0}}) ==
          std::vector<std::string>{"record.max_file_mb: must be between 0.001 and 1e+06"});
    CHECK(with_record({{"dir", "/var/tmp"}, {"max_file_mb", 10}, {"max_total_mb", 5}}) ==
          std::vector<std::string>{"record.max_total_mb: must be at least max_file_mb"});
    // Off unless present: no key, no recorder.
    const auto off = parse_config(valid_config().dump());
    REQUIRE(off.ok());
    CHECK_FALSE(off.config.record.has_value());
}
