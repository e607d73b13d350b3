#include "config.hpp"

#include "command/request_limits.hpp"
#include "mavlink/signing.hpp"
#include "protocols/registry.hpp"
#include "regular_file.hpp"
#include "secret_file.hpp"

#include <fmt/format.h>
#include <algorithm>
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
using config::join_path;
using config::Presence;
using config::Problems;

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

// The protocols a TCP link may find by broadcast discovery (host "discover").
std::string quoted_discovering_protocols() {
    std::vector<std::string_view> names;
    for (const auto* entry : gimbal::protocols::entries())
        if (entry->discovery) names.push_back(entry->name);
    return config::quoted_list(names);
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
    if (const auto* tcp = std::get_if<TcpLink>(&gimbal.link);
        tcp != nullptr && tcp->discover() && !own.discovery)
        f.problem("link.host", "\"discover\" only for a protocol with broadcast discovery (" +
                                   quoted_discovering_protocols() + ")");
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

// Contract section 14 (v4): every key file is checked here, as the per-gimbal one is, so a
// bad key is exit 1 of --check-config, not a failure (and restarts) at start.
void check_signing_key(const MavlinkConfig& mavlink, Problems& problems) {
    if (!mavlink.signing_key_file) return;
    const auto text = read_secret_file(*mavlink.signing_key_file);
    if (!text)
        problems.add("mavlink.signing_key_file", text.error().message);
    else if (!gimbal::mavlink::parse_signing_key(*text))
        problems.add("mavlink.signing_key_file",
                     *mavlink.signing_key_file + ": must hold 32 bytes, or 64 hex digits");
}

// What makes a text no configuration before any parsing: its size, a NUL byte (JSON text has
// none, and a parser might stop there and take what follows for nothing), its nesting depth
// (each level costs memory while parsing: a 5 MB unclosed array took 1.1 GB).
std::optional<std::string> text_problem(std::string_view text) {
    if (text.size() > max_config_bytes)
        return fmt::format("larger than {}: not a gimbald configuration",
                           size_text(max_config_bytes));
    if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
        const auto before = text.substr(0, nul);
        const std::size_t line =
            1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
        const auto last_newline = before.rfind('\n');
        const std::size_t column =
            last_newline == std::string_view::npos ? nul + 1 : nul - last_newline;
        return fmt::format("line {}, column {}: a NUL byte: not a JSON text file", line, column);
    }
    if (command::nested_deeper_than(text, command::max_json_depth))
        return fmt::format("JSON nested deeper than {} levels", command::max_json_depth);
    return std::nullopt;
}

}  // namespace

ConfigResult parse_config(std::string_view text, GimbalsSection gimbals) {
    ConfigResult result;
    Problems problems(result.problems);
    if (const auto problem = text_problem(text)) {
        result.problems.push_back({"", *problem});
        return result;
    }
    json document;
    try {
        document = parse_rejecting_duplicates(text, problems);
    } catch (const json::parse_error& e) {
        result.problems.push_back({"", syntax_problem(text, e)});
        return result;
    } catch (const json::exception& e) {
        // A number too large for a double ("1e999") is out_of_range, not a parse_error.
        std::string what = e.what();
        if (const auto bracket = what.find("] "); bracket != std::string::npos)
            what = what.substr(bracket + 2);
        result.problems.push_back({"", what});
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
    section(root, "command", [&](Fields& f) { fields(f, config.command); });
    section(root, "laser", [&](Fields& f) { fields(f, config.laser); });
    section(root, "stare", [&](Fields& f) { fields(f, config.stare); });
    section(root, "telemetry", [&](Fields& f) { fields(f, config.telemetry); });
    section(root, "log", [&](Fields& f) { fields(f, config.log); });
    optional_section(root, "vehicle", config.vehicle);
    section(root, "mavlink", [&](Fields& f) { fields(f, config.mavlink); });
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
    check_signing_key(config.mavlink, problems);
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
    // A regular file of at most 1 MiB (contract section 14, v4): /dev/zero or a FIFO named as
    // the configuration must not hang or exhaust the daemon, nor --check-config.
    const auto text = read_regular_file(path, max_config_bytes);
    if (!text) {
        ConfigResult result;
        result.problems.push_back({"", "cannot read " + text.error().message});
        return result;
    }
    return parse_config(*text, gimbals);
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

}  // namespace

json to_json(const Config& config, bool show_token) {
    json gimbals = json::array();
    for (const auto& gimbal : config.gimbals) gimbals.push_back(gimbal_to_json(gimbal));
    json out = {{"gimbals", gimbals},
                {"command", config::write(config.command)},
                {"laser", config::write(config.laser)},
                {"stare", config::write(config.stare)},
                {"telemetry", config::write(config.telemetry)},
                {"log", config::write(config.log)},
                {"mavlink", config::write(config.mavlink)}};
    if (config.command.token && !show_token) out["command"]["token"] = "***";
    if (config.vehicle) out["vehicle"] = config::write(*config.vehicle);
    if (config.mqtt) out["mqtt"] = config::write(*config.mqtt);
    if (config.http) out["http"] = config::write(*config.http);
    if (config.record) out["record"] = config::write(*config.record);
    if (config.terrain) out["terrain"] = config::write(*config.terrain);
    return out;
}

}  // namespace gimbal::daemon
