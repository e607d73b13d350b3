#include "options.hpp"

#include <CLI/CLI.hpp>

#include <fmt/format.h>
#include <algorithm>
#include <ostream>

#include "protocols/registry.hpp"
#include "terrain_model.hpp"

#ifndef GIMBALD_VERSION
#define GIMBALD_VERSION "0.0.0"
#endif

namespace gimbal::daemon {

namespace {

// The protocols as the registry lists them, each between `before` and `after`, joined by
// `separator`: display names or names.
std::string joined(std::string_view separator, std::string_view before, std::string_view after,
                   bool display) {
    std::string out;
    for (const auto* p : gimbal::protocols::entries())
        out += (out.empty() ? "" : std::string(separator)) + std::string(before) +
               std::string(display ? p->display_name : p->name) + std::string(after);
    return out;
}

std::string first_protocol() {
    return std::string(
        gimbal::protocols::entry(gimbal::protocols::all_protocol_ids.front()).display_name);
}

std::string name_line() {
    return "gimbald - ground-control daemon for camera gimbals (" + joined(", ", "", "", true) +
           ")";
}

constexpr const char* synopsis =
    "gimbald [-c FILE] [--sim [PROTOCOLS]] [--log-level LEVEL]\n"
    "        [--log-format FORMAT]\n"
    "gimbald --check-config [-c FILE] [--sim [PROTOCOLS]]\n"
    "gimbald --help | --version";

constexpr const char* description =
    "gimbald keeps a link open to every gimbal of its configuration file (TCP, serial port "
    "or an in-process simulation), decodes the telemetry into a state model and serves a "
    "JSON command socket (UDP, 127.0.0.1:8760 by default) for gimbalctl, scripts and "
    "ground-control software. Links reconnect by themselves; the laser stays safe whatever "
    "a client sends. Logs are one JSON object per line on standard output. Under systemd "
    "it reports readiness, status and watchdog keep-alives through NOTIFY_SOCKET.";

std::string examples() {
    return "EXAMPLES\n"
           "  gimbald -c /etc/gimbald/gimbald.json\n"
           "      Run with the installed configuration (what the systemd unit does).\n"
           "  gimbald --check-config -c my.json\n"
           "      Validate my.json, print every problem with its JSON path, exit 0 or 1.\n"
           "  gimbald --sim --log-format text\n"
           "      One simulated " +
           first_protocol() +
           " gimbal named \"sim\"; no configuration file is read.\n"
           "  gimbald --sim " +
           joined(",", "", "", false) +
           " -c my.json\n"
           "      Simulated gimbals " +
           joined(", ", "\"sim-", "\"", false) +
           ",\n"
           "      with the command, laser, log ... settings of my.json (its gimbals are\n"
           "      ignored).\n\n";
}

constexpr const char* footer = R"(EXIT STATUS
  0  clean stop (SIGTERM or SIGINT); --check-config: the configuration is valid
  1  configuration error: invalid file or command line
  2  runtime failure, e.g. the command port cannot be bound

SIGNALS
  SIGTERM, SIGINT  stop: lasers last commanded to fire get fire 0, links close
  SIGHUP           reopen log.file (after logrotate moved it)

FILES
  /etc/gimbald/gimbald.json  default configuration, see gimbald.json(5)

SEE ALSO
  gimbalctl(1), gimbal-sim(1), gimbal-replay(1), gimbal-export(1),
  gimbald.json(5), /usr/share/doc/gimbald/
)";

constexpr std::size_t help_width = 80;

// Word-wraps `text` to help_width, every line indented by `indent` spaces.
std::string wrap(std::string_view text, std::size_t indent) {
    std::string out;
    std::string line(indent, ' ');
    std::size_t start = 0;
    while (start < text.size()) {
        const auto end = std::min(text.find(' ', start), text.size());
        const auto word = text.substr(start, end - start);
        if (line.size() > indent && line.size() + 1 + word.size() > help_width) {
            out += line + "\n";
            line.assign(indent, ' ');
        }
        if (line.size() > indent) line += ' ';
        line += word;
        start = end + 1;
    }
    return out + line + "\n";
}

std::string indented(std::string_view lines, std::size_t indent) {
    std::string out;
    std::size_t start = 0;
    while (start < lines.size()) {
        const auto end = std::min(lines.find('\n', start), lines.size());
        out += std::string(indent, ' ') + std::string(lines.substr(start, end - start)) + "\n";
        start = end + 1;
    }
    return out;
}

// --help in the layout of a man page: NAME, SYNOPSIS, DESCRIPTION, OPTIONS (from the
// options themselves, so it cannot drift), then the footer sections.
std::string man_page(const CLI::App* app) {
    std::string out = "NAME\n" + wrap(name_line(), 2) + "\nSYNOPSIS\n" + indented(synopsis, 2) +
                      "\nDESCRIPTION\n" + wrap(description, 2) + "\nOPTIONS\n";
    for (const CLI::Option* option : app->get_options()) {
        std::string names;
        for (const auto& s : option->get_snames()) names += (names.empty() ? "-" : ", -") + s;
        for (const auto& l : option->get_lnames()) names += (names.empty() ? "--" : ", --") + l;
        // CLI11 appends the allowed values (":{json,text}") to the type; the text lists them.
        std::string argument = option->get_type_name();
        argument = argument.substr(0, argument.find(':'));
        out += "  " + names + (argument.empty() ? "" : " " + argument) + "\n";
        out += wrap(option->get_description(), 6);
    }
    return out + "\n" + app->get_footer();
}

}  // namespace

std::optional<std::vector<Protocol>> parse_sim_protocols(std::string_view list,
                                                         std::string& error) {
    std::vector<Protocol> protocols;
    if (list.empty()) return protocols;
    std::size_t start = 0;
    while (start <= list.size()) {
        const auto comma = std::min(list.find(',', start), list.size());
        const auto name = list.substr(start, comma - start);
        const auto protocol = parse_protocol(name);
        if (!protocol) {
            error = fmt::format("--sim: unknown protocol \"{}\" (expected {})", name,
                                gimbal::protocols::names_text());
            return std::nullopt;
        }
        if (std::find(protocols.begin(), protocols.end(), *protocol) != protocols.end()) {
            error = fmt::format("--sim: protocol \"{}\" listed twice", name);
            return std::nullopt;
        }
        protocols.push_back(*protocol);
        start = comma + 1;
    }
    return protocols;
}

CommandLine parse_command_line(int argc, const char* const* argv, std::ostream& out,
                               std::ostream& err) {
    CommandLine result;
    Options& options = result.options;

    CLI::App app{description, "gimbald"};
    app.footer(examples() + footer);
    app.formatter_fn(
        [](const CLI::App* a, std::string, CLI::AppFormatMode) { return man_page(a); });
    app.set_help_flag("-h,--help", "Print this help and exit.");

    std::string sim_list;
    std::string log_level;
    std::string log_format;
    bool version = false;

    auto* config = app.add_option("-c,--config", options.config_path,
                                  "Configuration file (JSON; every key is described in "
                                  "docs/configuration.md). Default: /etc/gimbald/gimbald.json; "
                                  "not read under --sim unless given.")
                       ->type_name("FILE");
    auto* sim = app.add_option("--sim", sim_list,
                               "Serve simulated gimbals in-process instead of the file's "
                               "gimbals. Alone: one " +
                                   first_protocol() + " named \"sim\"; with a list such as " +
                                   joined(",", "", "", false) + ": gimbals " +
                                   joined(", ", "\"sim-", "\"", false) + ". Default: off.")
                    ->expected(0, 1)
                    ->type_name("[PROTOCOLS]");
    app.add_flag("--check-config", options.check_config,
                 "Validate the configuration, print every problem with its JSON path, exit 0 if "
                 "valid, 1 if not. Reads every key file and opens every terrain file, no "
                 "device. Default: off.");
    app.add_option("--log-level", log_level,
                   "trace, debug, info, warn or error; overrides log.level. "
                   "Default: the file's (info).")
        ->type_name("LEVEL")
        ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
    app.add_option("--log-format", log_format,
                   "json or text; overrides log.format. Default: the file's (json).")
        ->type_name("FORMAT")
        ->check(CLI::IsMember({"json", "text"}));
    app.add_flag("--version", version, "Print the version and exit.");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        out << app.help();
        result.exit_code = exit_ok;
        return result;
    } catch (const CLI::ParseError& e) {
        err << "gimbald: " << e.what() << "\nRun 'gimbald --help' for the options.\n";
        result.exit_code = exit_config_error;
        return result;
    }

    if (version) {
        out << "gimbald " << GIMBALD_VERSION << "\n";
        result.exit_code = exit_ok;
        return result;
    }
    options.config_given = config->count() > 0;
    options.sim = sim->count() > 0;
    if (options.sim) {
        std::string error;
        auto protocols = parse_sim_protocols(sim_list, error);
        if (!protocols) {
            err << "gimbald: " << error << "\n";
            result.exit_code = exit_config_error;
            return result;
        }
        options.sim_protocols = std::move(*protocols);
    }
    if (!log_level.empty()) options.log_level = log::parse_level(log_level);
    if (!log_format.empty()) options.log_format = log::parse_format(log_format);
    return result;
}

ConfigResult resolve_config(const Options& options) {
    ConfigResult result;
    if (!options.sim || options.config_given) {
        result = load_config_file(options.config_path,
                                  options.sim ? GimbalsSection::ignored : GimbalsSection::required);
    }
    if (options.sim)
        result.config.gimbals = sim_gimbals(options.sim_protocols, result.config.gimbals);
    if (options.log_level) result.config.log.level = *options.log_level;
    if (options.log_format) result.config.log.format = *options.log_format;
    return result;
}

std::string config_source(const Options& options) {
    if (options.sim && !options.config_given) return "built-in --sim";
    return options.config_path;
}

int check_config(const Options& options, std::ostream& out, std::ostream& err) {
    auto result = resolve_config(options);
    // Terrain files are configuration, not devices: opened here too (section 15).
    OpenedTerrain terrain;
    if (result.ok()) {
        terrain = open_terrain(result.config);
        if (terrain.problem) result.problems.push_back(*terrain.problem);
    }
    const std::string source = config_source(options);
    if (!result.ok()) {
        for (const auto& problem : result.problems) err << source << ": " << problem.text() << "\n";
        err << fmt::format("{}: {} problem{}\n", source, result.problems.size(),
                           result.problems.size() == 1 ? "" : "s");
        return exit_config_error;
    }
    std::string gimbals;
    for (const auto& gimbal : result.config.gimbals) {
        const bool sim = std::holds_alternative<SimLink>(gimbal.link);
        gimbals += fmt::format("{}{} ({}, {}{}{})", gimbals.empty() ? "" : ", ", gimbal.name,
                               to_string(gimbal.protocol), link_type(gimbal.link), sim ? "" : " ",
                               sim ? "" : describe(gimbal.link));
    }
    std::string dem;
    if (terrain.model)
        dem = fmt::format("; terrain: {} file{}", terrain.model->files().size(),
                          terrain.model->files().size() == 1 ? "" : "s");
    out << fmt::format("{}: OK, {} gimbal{}{}{}{}\n", source, result.config.gimbals.size(),
                       result.config.gimbals.size() == 1 ? "" : "s", gimbals.empty() ? "" : ": ",
                       gimbals, dem);
    return exit_ok;
}

}  // namespace gimbal::daemon
