#include "config.hpp"

#include "auth/roles.hpp"
#include "auth/secret.hpp"
#include "mqtt/mqtt_url.hpp"
#include "protocols/registry.hpp"
#include "secret_file.hpp"
#include "state/messages.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <regex>
#include <set>
#include <utility>

namespace gimbal::daemon {

namespace {

using nlohmann::json;

// The generic reader and writer: lib/config/fields.hpp.
using config::Fields;
using config::index_path;
using config::IntRange;
using config::join_path;
using config::Presence;
using config::Problems;
using config::Range;

// nlohmann keeps the last of two equal keys without a word; in a configuration that is a
// silent override ("allow_fire" twice), so it is reported with its path.
json parse_rejecting_duplicates(std::string_view text, Problems& problems) {
    struct Container {
        bool is_array = false;
        std::set<std::string> keys;
        std::string key;        // objects: the member being parsed
        std::size_t index = 0;  // arrays: the element being parsed
    };
    std::vector<Container> stack;
    auto path_to_top = [&stack] {
        std::string path;
        for (std::size_t i = 0; i + 1 < stack.size(); ++i) {
            path = stack[i].is_array ? index_path(path, stack[i].index)
                                     : join_path(path, stack[i].key);
        }
        return path;
    };
    auto element_done = [&stack] {
        if (!stack.empty() && stack.back().is_array) ++stack.back().index;
    };
    using event = json::parse_event_t;
    auto callback = [&](int, event e, json& parsed) {
        switch (e) {
            case event::object_start:
                stack.push_back({false, {}, {}, 0});
                break;
            case event::array_start:
                stack.push_back({true, {}, {}, 0});
                break;
            case event::key: {
                auto& top = stack.back();
                top.key = parsed.get<std::string>();
                if (!top.keys.insert(top.key).second) {
                    problems.add(join_path(path_to_top(), top.key), "duplicate key");
                }
                break;
            }
            case event::object_end:
            case event::array_end:
                stack.pop_back();
                element_done();
                break;
            case event::value:
                element_done();
                break;
        }
        return true;
    };
    return json::parse(text.begin(), text.end(), callback);
}

// ---- The configuration sections ---------------------------------------------------------

constexpr std::size_t max_gimbals = 32;

// `video` (contract section 17): its reading is daemon/video/video_config.cpp's.
void read_video(Fields& f, GimbalConfig& gimbal) {
    const json* video = f.find("video");
    if (video == nullptr || video->is_null()) return;
    if (!video->is_object()) {
        f.problem("video", "must be an object with at least \"input\"");
        return;
    }
    f.section("video", [&gimbal](Fields& v) { fields(v, gimbal.video.emplace()); });
}

// Under --sim the file's gimbals are replaced, but their `video` sections still apply to
// the simulated gimbal of the same protocol (sim_gimbals): only `protocol` and `video` are
// read, and only a video section's problems are reported.
void read_sim_videos(Fields& root, Config& config) {
    const json* list = root.find("gimbals");
    if (list == nullptr || !list->is_array()) return;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const json& item = (*list)[i];
        if (!item.is_object() || !item.contains("protocol") || !item["protocol"].is_string())
            continue;
        const auto protocol = parse_protocol(item["protocol"].get<std::string>());
        if (!protocol) continue;
        Fields f(item, index_path("gimbals", i), root.problems());
        GimbalConfig gimbal;
        gimbal.protocol = *protocol;
        read_video(f, gimbal);
        if (gimbal.video) config.gimbals.push_back(std::move(gimbal));
    }
}

using ProtocolConfigContext = gimbal::protocols::ConfigContext;

// "\"orion\", \"viewpro\", ..." in the registry's order.
std::string quoted_protocols() {
    const auto names = gimbal::protocols::names();
    const std::vector<std::string_view> views(names.begin(), names.end());
    return config::quoted_list(views);
}

GimbalConfig read_gimbal(Fields& f, const ProtocolConfigContext& context) {
    static const std::regex name_pattern("[a-z0-9_-]{1,32}");
    GimbalConfig gimbal;
    if (f.string("name", gimbal.name, Presence::required) &&
        !std::regex_match(gimbal.name, name_pattern)) {
        f.problem("name", "must match [a-z0-9_-]{1,32}");
    }
    bool known_protocol = false;
    if (const json* value = f.required("protocol")) {
        const auto* named =
            value->is_string() ? gimbal::protocols::find(value->get<std::string>()) : nullptr;
        if (named == nullptr)
            f.problem("protocol", "must be one of " + quoted_protocols());
        else
            gimbal.protocol = named->id;
        known_protocol = named != nullptr;
    }

    if (auto link = f.object("link", Presence::required)) {
        if (auto parsed = read_link(*link)) gimbal.link = *parsed;
        link->finish();
    }

    if (!known_protocol) {
        f.keep_unknown_keys();  // the protocol's own keys depend on the protocol
        return gimbal;
    }
    const auto& own = gimbal::protocols::entry(gimbal.protocol);
    gimbal.protocol_config = own.read_config(f, context);
    for (const auto* other : gimbal::protocols::entries()) {
        if (other == &own || other->config_section.empty()) continue;
        if (other->config_section == own.config_section) continue;
        if (f.find(other->config_section) != nullptr)
            f.problem(other->config_section,
                      "only for protocol \"" + std::string(other->name) + "\"");
    }
    read_video(f, gimbal);
    return gimbal;
}

void read_gimbals(Fields& root, Config& config) {
    const ProtocolConfigContext context{
        [](const std::string& path) { return read_secret_file(path); }};
    const json* list = root.required("gimbals");
    if (list == nullptr) return;
    if (!list->is_array()) {
        root.problem("gimbals", "must be an array of gimbals");
        return;
    }
    // An empty list is valid: the packaged /etc/gimbald/gimbald.json starts with no gimbals.
    if (list->size() > max_gimbals) {
        root.problem("gimbals", fmt::format("must list 0 to {} gimbals", max_gimbals));
    }
    std::map<std::string, std::string> first_path_of_name;
    std::map<std::string, std::string> first_path_of_device;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const std::string path = index_path("gimbals", i);
        Fields f((*list)[i], path, root.problems());
        if (!f.is_object()) continue;
        GimbalConfig gimbal = read_gimbal(f, context);
        f.finish();

        if (!gimbal.name.empty()) {
            auto [it, fresh] = first_path_of_name.emplace(gimbal.name, path);
            if (!fresh) {
                f.problem("name",
                          fmt::format("duplicate name \"{}\" (also {})", gimbal.name, it->second));
            }
        }
        if (const auto* serial = std::get_if<SerialLink>(&gimbal.link);
            serial != nullptr && !serial->device.empty()) {
            auto [it, fresh] = first_path_of_device.emplace(serial->device, path);
            if (!fresh) {
                f.problem("link.device",
                          fmt::format("\"{}\" is already used by {}", serial->device, it->second));
            }
        }
        config.gimbals.push_back(std::move(gimbal));
    }
}

bool valid_key_id(const std::string& id) {
    if (id.empty() || id.size() > 64) return false;
    return std::all_of(id.begin(), id.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.';
    });
}

CommandKey read_key(Fields& f) {
    CommandKey key;
    if (f.string("id", key.id, Presence::required) && !valid_key_id(key.id))
        f.problem("id", "must be 1 to 64 characters of A-Z a-z 0-9 _ - .");
    if (f.string("secret_file", key.secret_file, Presence::required)) {
        const auto text = read_secret_file(key.secret_file);
        if (!text) {
            f.problem("secret_file", text.error().message);
        } else {
            auto secret = gimbal::auth::parse_secret(*text);
            if (auto* bytes = std::get_if<std::vector<std::uint8_t>>(&secret))
                key.secret = std::move(*bytes);
            else
                f.problem("secret_file", key.secret_file + ": " + std::get<std::string>(secret));
        }
    }
    if (const json* roles = f.required("roles")) {
        if (!roles->is_array() || roles->empty()) {
            f.problem("roles", "must be a non-empty array of \"observe\", \"control\", \"laser\"");
        } else {
            for (std::size_t i = 0; i < roles->size(); ++i) {
                const json& r = (*roles)[i];
                if (r.is_string() && gimbal::auth::parse_role(r.get_ref<const std::string&>()))
                    key.roles.push_back(r.get<std::string>());
                else
                    f.problems().add(index_path(f.path("roles"), i),
                                     "must be \"observe\", \"control\" or \"laser\"");
            }
        }
    }
    f.finish();
    return key;
}

void read_auth(Fields& f, CommandConfig& command) {
    std::string auth;
    if (f.choice("auth", auth, {"none", "signed"}))
        command.auth = auth == "signed" ? AuthMode::signed_requests : AuthMode::none;
    if (const json* keys = f.find("keys"); keys != nullptr && !keys->is_null()) {
        if (!keys->is_array()) {
            f.problem("keys", "must be an array of {\"id\", \"secret_file\", \"roles\"}");
        } else {
            for (std::size_t i = 0; i < keys->size(); ++i) {
                Fields k((*keys)[i], index_path(f.path("keys"), i), f.problems());
                if (!k.is_object()) continue;
                CommandKey key = read_key(k);
                const bool duplicate =
                    std::any_of(command.keys.begin(), command.keys.end(),
                                [&key](const CommandKey& other) { return other.id == key.id; });
                if (duplicate)
                    f.problems().add(index_path(f.path("keys"), i) + ".id",
                                     "duplicate key id \"" + key.id + "\"");
                command.keys.push_back(std::move(key));
            }
        }
    }
    f.number("max_skew_s", command.max_skew_s, {1, 3600});
    if (auto rate = f.object("rate_limit")) {
        rate->number("per_source_hz", command.rate_limit.per_source_hz, {0.1, 100000});
        rate->number("burst", command.rate_limit.burst, {1, 1000000});
        rate->finish();
    }
    if (command.token && !command.keys.empty())
        f.problem("keys", "\"token\" and \"keys\" may not both be set: choose one");
    if (command.auth == AuthMode::signed_requests && command.keys.empty())
        f.problem("auth", "\"signed\" needs at least one key in command.keys");
}

void read_command(Fields& f, CommandConfig& command) {
    read_address(f, "bind", command.bind);
    f.integer("port", command.port, {1, 65535});
    if (const json* allow = f.find("allow")) {
        if (!allow->is_array() || allow->empty()) {
            f.problem("allow", "must be a non-empty array of CIDR blocks such as \"127.0.0.0/8\"");
        } else {
            command.allow.clear();
            for (std::size_t i = 0; i < allow->size(); ++i) {
                const json& item = (*allow)[i];
                std::optional<Cidr> cidr;
                if (item.is_string()) cidr = Cidr::parse(item.get_ref<const std::string&>());
                if (cidr) {
                    command.allow.push_back(*cidr);
                } else {
                    f.problems().add(index_path(f.path("allow"), i), "not a CIDR");
                }
            }
        }
    }
    if (const json* token = f.find("token"); token != nullptr && !token->is_null()) {
        if (!token->is_string() || token->get_ref<const std::string&>().empty() ||
            token->get_ref<const std::string&>().size() > 256) {
            f.problem("token", "must be null or a string of 1 to 256 characters");
        } else {
            command.token = token->get<std::string>();
        }
    }
    f.integer("max_subscribers", command.max_subscribers, {1, 1024});
    f.integer("max_subscribers_per_host", command.max_subscribers_per_host, {1, 1024});
    read_auth(f, command);
}

void read_log(Fields& f, LogConfig& log) {
    std::string level;
    if (f.choice("level", level, {"trace", "debug", "info", "warn", "error"})) {
        log.level = *log::parse_level(level);
    }
    std::string format;
    if (f.choice("format", format, {"json", "text"})) log.format = *log::parse_format(format);
    if (const json* file = f.find("file"); file != nullptr && !file->is_null()) {
        if (!file->is_string() || file->get_ref<const std::string&>().empty()) {
            f.problem("file", "must be null or a file path");
        } else {
            log.file = file->get<std::string>();
        }
    }
}

VehicleConfig read_vehicle(Fields& f) {
    VehicleConfig vehicle;
    if (auto source = f.object("source")) {
        std::string type;
        if (source->choice("type", type, {"udp", "serial"}, Presence::required)) {
            if (type == "udp") {
                UdpSource udp;
                read_address(*source, "bind", udp.bind);
                source->integer("port", udp.port, {1, 65535});
                vehicle.source = udp;
            } else {
                SerialSource serial;
                read_device(*source, "device", serial.device);
                read_baud(*source, "baud", serial.baud);
                vehicle.source = serial;
            }
            source->finish();
        }
    }
    if (const json* id = f.find("system_id"); id != nullptr && !id->is_null()) {
        std::uint8_t system_id = 0;
        f.integer("system_id", system_id, {1, 255});
        if (system_id != 0) vehicle.system_id = system_id;
    }
    f.number("timeout_s", vehicle.timeout_s, {0.1, 60});
    return vehicle;
}

void read_mavlink(Fields& f, MavlinkConfig& m) {
    f.boolean("gimbal_manager", m.gimbal_manager);
    if (const json* id = f.find("system_id"); id != nullptr && !id->is_null()) {
        std::uint8_t system_id = 0;
        if (f.integer("system_id", system_id, {1, 255})) m.system_id = system_id;
    }
    f.integer("component_id", m.component_id, {1, 255});
    if (const json* targets = f.find("targets")) {
        if (!targets->is_array()) {
            f.problem("targets", "must be an array of \"host:port\" strings");
        } else {
            for (std::size_t i = 0; i < targets->size(); ++i) {
                const json& t = (*targets)[i];
                const std::string text = t.is_string() ? t.get<std::string>() : std::string();
                const auto colon = text.rfind(':');
                int port = 0;
                if (colon != std::string::npos && colon > 0) {
                    const std::string digits = text.substr(colon + 1);
                    if (!digits.empty() && digits.size() <= 5 &&
                        digits.find_first_not_of("0123456789") == std::string::npos)
                        port = std::stoi(digits);
                }
                if (port < 1 || port > 65535)
                    f.problems().add(index_path(f.path("targets"), i),
                                     "must be \"host:port\" with a port 1..65535");
                else
                    m.targets.push_back(text);
            }
        }
    }
    for (const auto& [key, target] : {std::pair{"signing_key_file", &m.signing_key_file},
                                      std::pair{"signing_state_file", &m.signing_state_file}}) {
        if (const json* v = f.find(key); v != nullptr && !v->is_null()) {
            if (!v->is_string() || v->get_ref<const std::string&>().empty())
                f.problem(key, "must be null or a file path");
            else
                *target = v->get<std::string>();
        }
    }
    f.boolean("commands", m.commands);
    if (const json* alt = f.find("home_alt_msl"); alt != nullptr && !alt->is_null()) {
        double home = 0;
        if (f.number("home_alt_msl", home, {-1000, 10000})) m.home_alt_msl = home;
    }
}

// Object sections with no cross-dependencies: read each when present.
template <class Read>
void section(Fields& root, std::string_view key, Read read) {
    if (auto f = root.object(key)) {
        read(*f);
        f->finish();
    }
}

// A section that is off unless present: read through its fields() when it is.
template <class Section>
void optional_section(Fields& root, std::string_view key, std::optional<Section>& out) {
    section(root, key, [&out](Fields& f) { fields(f, out.emplace()); });
}

void check_serial_devices_unique(const Config& config, Problems& problems) {
    if (!config.vehicle) return;
    const auto* source = std::get_if<SerialSource>(&config.vehicle->source);
    if (source == nullptr || source->device.empty()) return;
    for (std::size_t i = 0; i < config.gimbals.size(); ++i) {
        const auto* link = std::get_if<SerialLink>(&config.gimbals[i].link);
        if (link != nullptr && link->device == source->device) {
            problems.add("vehicle.source.device",
                         fmt::format("\"{}\" is already used by gimbals[{}]", source->device, i));
        }
    }
}

std::string syntax_problem(std::string_view text, const json::parse_error& e) {
    // nlohmann counts the byte it stopped at; report it as line:column (1-based).
    const std::size_t end = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    std::size_t line = 1;
    std::size_t column = 1;
    for (std::size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    std::string what = e.what();
    // "[json.exception.parse_error.101] parse error at line 3, column 15: syntax error ..."
    if (auto colon = what.find(": ", what.find("parse error")); colon != std::string::npos) {
        what = what.substr(colon + 2);
    }
    return fmt::format("line {}, column {}: {}", line, column, what);
}

}  // namespace

std::optional<Cidr> Cidr::parse(std::string_view text) {
    const auto slash = text.find('/');
    boost::system::error_code ec;
    const auto address = boost::asio::ip::make_address(std::string(text.substr(0, slash)), ec);
    if (ec) return std::nullopt;
    const unsigned max_prefix = address.is_v4() ? 32 : 128;
    unsigned prefix = max_prefix;
    if (slash != std::string_view::npos) {
        const auto digits = text.substr(slash + 1);
        if (digits.empty() || digits.size() > 3 ||
            !std::all_of(digits.begin(), digits.end(),
                         [](char c) { return c >= '0' && c <= '9'; })) {
            return std::nullopt;
        }
        prefix = static_cast<unsigned>(std::stoul(std::string(digits)));
        if (prefix > max_prefix) return std::nullopt;
    }
    Cidr cidr{address, prefix};
    // Clear the host bits so equal blocks compare equal and print canonically.
    if (address.is_v4()) {
        auto bytes = address.to_v4().to_bytes();
        for (std::size_t i = 0; i < bytes.size(); ++i) {
            const unsigned keep = std::min(8u, prefix - std::min(prefix, unsigned(i * 8)));
            bytes[i] = static_cast<unsigned char>(bytes[i] & (0xFF00u >> keep));
        }
        cidr.network = boost::asio::ip::address_v4(bytes);
    } else {
        auto bytes = address.to_v6().to_bytes();
        for (std::size_t i = 0; i < bytes.size(); ++i) {
            const unsigned keep = std::min(8u, prefix - std::min(prefix, unsigned(i * 8)));
            bytes[i] = static_cast<unsigned char>(bytes[i] & (0xFF00u >> keep));
        }
        cidr.network = boost::asio::ip::address_v6(bytes);
    }
    return cidr;
}

bool Cidr::contains(const boost::asio::ip::address& address) const {
    auto candidate = address;
    if (candidate.is_v6() && candidate.to_v6().is_v4_mapped()) {
        candidate = boost::asio::ip::make_address_v4(boost::asio::ip::v4_mapped, candidate.to_v6());
    }
    if (candidate.is_v4() != network.is_v4()) return false;
    auto matches = [this](const auto& a, const auto& b) {
        for (std::size_t i = 0; i < a.size(); ++i) {
            const unsigned keep =
                std::min(8u, prefix_length - std::min(prefix_length, unsigned(i * 8)));
            const unsigned mask = 0xFF00u >> keep;
            if (((a[i] ^ b[i]) & mask) != 0) return false;
        }
        return true;
    };
    if (network.is_v4()) return matches(network.to_v4().to_bytes(), candidate.to_v4().to_bytes());
    return matches(network.to_v6().to_bytes(), candidate.to_v6().to_bytes());
}

std::string Cidr::to_string() const {
    return fmt::format("{}/{}", network.to_string(), prefix_length);
}

std::vector<Cidr> CommandConfig::default_allow() {
    return {*Cidr::parse("127.0.0.0/8"), *Cidr::parse("::1/128")};
}

bool CommandConfig::allowed(const boost::asio::ip::address& source) const {
    return std::any_of(allow.begin(), allow.end(),
                       [&](const Cidr& cidr) { return cidr.contains(source); });
}

ConfigResult parse_config(std::string_view text, GimbalsSection gimbals) {
    ConfigResult result;
    Problems problems(result.problems);
    json document;
    try {
        document = parse_rejecting_duplicates(text, problems);
    } catch (const json::parse_error& e) {
        result.problems.push_back({"", syntax_problem(text, e)});
        return result;
    }
    if (!document.is_object()) {
        problems.add("", "the configuration must be a JSON object");
        return result;
    }

    Config& config = result.config;
    Fields root(document, "", problems);
    if (gimbals == GimbalsSection::required) {
        read_gimbals(root, config);
    } else {
        read_sim_videos(root, config);  // replaced by --sim: only their video sections count
    }
    section(root, "command", [&](Fields& f) { read_command(f, config.command); });
    section(root, "laser", [&](Fields& f) {
        f.boolean("allow_fire", config.laser.allow_fire);
        f.number("fire_timeout_s", config.laser.fire_timeout_s, {0.1, 3600});
        f.boolean("allow_safety_bypass", config.laser.allow_safety_bypass);
    });
    section(root, "stare", [&](Fields& f) { f.boolean("auto_ack", config.stare.auto_ack); });
    section(root, "telemetry", [&](Fields& f) {
        f.number("stale_after_s", config.telemetry.stale_after_s, {0.1, 60});
    });
    section(root, "log", [&](Fields& f) { read_log(f, config.log); });
    section(root, "vehicle", [&](Fields& f) { config.vehicle = read_vehicle(f); });
    section(root, "mavlink", [&](Fields& f) { read_mavlink(f, config.mavlink); });
    optional_section(root, "mqtt", config.mqtt);
    optional_section(root, "http", config.http);
    optional_section(root, "record", config.record);
    optional_section(root, "terrain", config.terrain);
    root.finish();
    // POST /api/command reaches the laser like a datagram: the same start-up refusal.
    if (config.http && config.laser.allow_fire && !config.http->bind.is_loopback() &&
        config.command.auth == AuthMode::none)
        problems.add("http.bind", "laser.allow_fire is true and http.bind (" +
                                      config.http->bind.to_string() +
                                      ") is not a loopback address: anyone on that network "
                                      "could fire the laser; set command.auth to \"signed\" or "
                                      "bind to 127.0.0.1");
    if (config.mavlink.gimbal_manager && !config.vehicle)
        problems.add("mavlink.gimbal_manager",
                     "needs a vehicle section: the gimbal manager talks on vehicle.source");
    // Contract section 14: signed requests everywhere means signed MAVLink commands too.
    if (config.command.auth == AuthMode::signed_requests && config.mavlink.gimbal_manager &&
        config.mavlink.commands && !config.mavlink.signing_key_file)
        problems.add("mavlink.signing_key_file",
                     "command.auth is \"signed\" but MAVLink commands would be obeyed unsigned: "
                     "set mavlink.signing_key_file, or mavlink.commands to false (the gimbal "
                     "manager then only reports)");
    check_serial_devices_unique(config, problems);
    if (config.laser.allow_fire && !config.command.bind.is_loopback() &&
        config.command.auth == AuthMode::none)
        problems.add("command.auth",
                     "laser.allow_fire is true and command.bind (" +
                         config.command.bind.to_string() +
                         ") is not a loopback address: anyone on that network could fire the "
                         "laser; set command.auth to \"signed\" or bind to 127.0.0.1");
    return result;
}

ConfigResult load_config_file(const std::string& path, GimbalsSection gimbals) {
    std::FILE* file = std::fopen(path.c_str(), "rbe");
    if (file == nullptr) {
        const std::string reason = std::strerror(errno);  // before anything resets errno
        ConfigResult result;
        result.problems.push_back({"", fmt::format("cannot read {}: {}", path, reason)});
        return result;
    }
    std::string text;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, file)) > 0;)
        text.append(buffer, n);
    const bool failed = std::ferror(file) != 0;
    const int error = errno;
    std::fclose(file);
    if (failed) {
        const std::string reason = std::strerror(error);
        ConfigResult result;
        result.problems.push_back({"", fmt::format("cannot read {}: {}", path, reason)});
        return result;
    }
    return parse_config(text, gimbals);
}

json protocol_defaults(Protocol protocol) {
    std::vector<Problem> none;
    Problems problems(none);
    const json empty = json::object();
    Fields f(empty, "", problems);
    return gimbal::protocols::entry(protocol).read_config(f, {});
}

std::vector<GimbalConfig> sim_gimbals(std::span<const Protocol> protocols,
                                      const std::vector<GimbalConfig>& file_gimbals) {
    auto simulated = [](std::string name, Protocol protocol) {
        GimbalConfig gimbal;
        gimbal.name = std::move(name);
        gimbal.protocol = protocol;
        gimbal.link = SimLink{};
        gimbal.protocol_config = protocol_defaults(protocol);
        return gimbal;
    };
    std::vector<GimbalConfig> gimbals;
    if (protocols.empty())
        gimbals.push_back(simulated("sim", gimbal::protocols::all_protocol_ids.front()));
    for (Protocol protocol : protocols) {
        gimbals.push_back(simulated(fmt::format("sim-{}", to_string(protocol)), protocol));
    }
    for (auto& gimbal : gimbals) {
        for (const auto& from : file_gimbals) {
            if (from.protocol != gimbal.protocol || !from.video) continue;
            gimbal.video = from.video;
            break;
        }
    }
    return gimbals;
}

namespace {

json gimbal_to_json(const GimbalConfig& gimbal) {
    json out = {{"name", gimbal.name},
                {"protocol", to_string(gimbal.protocol)},
                {"link", write_link(gimbal.link)}};
    out.update(gimbal.protocol_config);  // its protocol's own keys, every default present
    if (gimbal.video) out["video"] = config::write(*gimbal.video);
    return out;
}

json vehicle_to_json(const VehicleConfig& vehicle) {
    json source;
    if (const auto* udp = std::get_if<UdpSource>(&vehicle.source)) {
        source = {{"type", "udp"}, {"bind", udp->bind.to_string()}, {"port", udp->port}};
    } else {
        const auto& serial = std::get<SerialSource>(vehicle.source);
        source = {{"type", "serial"}, {"device", serial.device}, {"baud", serial.baud}};
    }
    return {{"source", source},
            {"system_id", vehicle.system_id ? json(*vehicle.system_id) : json(nullptr)},
            {"timeout_s", vehicle.timeout_s}};
}

}  // namespace

json to_json(const Config& config, bool show_token) {
    json gimbals = json::array();
    for (const auto& gimbal : config.gimbals) gimbals.push_back(gimbal_to_json(gimbal));
    json allow = json::array();
    for (const auto& cidr : config.command.allow) allow.push_back(cidr.to_string());
    json token = nullptr;
    if (config.command.token) token = show_token ? *config.command.token : "***";
    // Secrets stay in their files: only where they are is shown.
    json keys = json::array();
    for (const auto& key : config.command.keys)
        keys.push_back({{"id", key.id}, {"secret_file", key.secret_file}, {"roles", key.roles}});

    json out = {
        {"gimbals", gimbals},
        {"command",
         {{"bind", config.command.bind.to_string()},
          {"port", config.command.port},
          {"allow", allow},
          {"token", token},
          {"max_subscribers", config.command.max_subscribers},
          {"max_subscribers_per_host", config.command.max_subscribers_per_host},
          {"auth", config.command.auth == AuthMode::signed_requests ? "signed" : "none"},
          {"keys", keys},
          {"max_skew_s", config.command.max_skew_s},
          {"rate_limit",
           {{"per_source_hz", config.command.rate_limit.per_source_hz},
            {"burst", config.command.rate_limit.burst}}}}},
        {"laser",
         {{"allow_fire", config.laser.allow_fire},
          {"fire_timeout_s", config.laser.fire_timeout_s},
          {"allow_safety_bypass", config.laser.allow_safety_bypass}}},
        {"stare", {{"auto_ack", config.stare.auto_ack}}},
        {"telemetry", {{"stale_after_s", config.telemetry.stale_after_s}}},
        {"log",
         {{"level", log::to_string(config.log.level)},
          {"format", log::to_string(config.log.format)},
          {"file", config.log.file ? json(*config.log.file) : json(nullptr)}}},
    };
    if (config.vehicle) out["vehicle"] = vehicle_to_json(*config.vehicle);
    const MavlinkConfig& m = config.mavlink;
    out["mavlink"] = {
        {"gimbal_manager", m.gimbal_manager},
        {"system_id", m.system_id ? json(*m.system_id) : json(nullptr)},
        {"component_id", m.component_id},
        {"targets", m.targets},
        {"signing_key_file", m.signing_key_file ? json(*m.signing_key_file) : json(nullptr)},
        {"commands", m.commands},
        {"home_alt_msl", m.home_alt_msl ? json(*m.home_alt_msl) : json(nullptr)},
        {"signing_state_file", m.signing_state_file ? json(*m.signing_state_file) : json(nullptr)}};
    if (config.mqtt) out["mqtt"] = config::write(*config.mqtt);
    if (config.http) out["http"] = config::write(*config.http);
    if (config.record) out["record"] = config::write(*config.record);
    if (config.terrain) out["terrain"] = config::write(*config.terrain);
    return out;
}

}  // namespace gimbal::daemon
