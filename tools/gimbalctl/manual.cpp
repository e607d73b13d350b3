#include "manual.hpp"

#include <algorithm>
#include <cctype>
#include <memory>
#include <sstream>
#include <vector>

#include <CLI/CLI.hpp>

namespace gimbalctl {
namespace {

constexpr std::size_t page_width = 80;
constexpr std::size_t body_indent = 7;     // text under a section heading
constexpr std::size_t detail_indent = 14;  // text under an option or command

// Word-wraps `text` at page_width: the first line of each paragraph ('\n' starts one) is
// indented by `indent`, the lines after it by `hanging`.
std::string wrap(const std::string& text, std::size_t indent, std::size_t hanging) {
    std::ostringstream out;
    std::istringstream paragraphs(text);
    std::string paragraph;
    bool first_paragraph = true;
    while (std::getline(paragraphs, paragraph)) {
        if (!first_paragraph) out << '\n';
        first_paragraph = false;
        std::istringstream words(paragraph);
        std::string word;
        std::size_t column = 0;
        std::size_t line_indent = indent;
        while (words >> word) {
            if (column > 0 && column + 1 + word.size() > page_width) {
                out << '\n';
                column = 0;
                line_indent = hanging;
            }
            if (column == 0) {
                out << std::string(line_indent, ' ') << word;
                column = line_indent + word.size();
            } else {
                out << ' ' << word;
                column += 1 + word.size();
            }
        }
        out << '\n';
    }
    return out.str();
}

std::string wrap(const std::string& text, std::size_t indent) {
    return wrap(text, indent, indent);
}

// "REF" from "REF", the choices "{wgs84,msl}" from "TEXT:{wgs84,msl}".
std::string value_name(const CLI::Option* option) {
    const std::string type = option->get_type_name();
    const auto brace = type.find('{');
    if (brace != std::string::npos) return type.substr(brace);
    return type.substr(0, type.find(':'));
}

// "-h, --help" (separator ", ") or "--stabilized|--no-stabilized" (separator "|").
std::string option_names(const CLI::Option* option, const std::string& separator) {
    std::string names;
    for (const std::string& name : option->get_snames()) {
        names += (names.empty() ? "-" : separator + "-") + name;
    }
    for (const std::string& name : option->get_lnames()) {
        names += (names.empty() ? "--" : separator + "--") + name;
    }
    return names;
}

// " VALUE" for an option that takes one, "" for a flag.
std::string value_suffix(const CLI::Option* option) {
    const std::string name = value_name(option);
    return name.empty() ? std::string{} : " " + name;
}

// How an option or positional is written in a synopsis: "LAT", "[POINT...]", "--osd WHAT",
// "[--vel-ned N E D]".
std::string usage_of(const CLI::Option* option) {
    std::string usage;
    if (option->get_positional()) {
        usage = option->get_name(true, false);
        if (option->get_expected_max() > 1) usage += "...";
    } else {
        usage = option_names(option, "|") + value_suffix(option);
    }
    return option->get_required() ? usage : "[" + usage + "]";
}

std::vector<const CLI::Option*> visible_options(const CLI::App* app, bool positional) {
    return app->get_options([app, positional](const CLI::Option* option) {
        return option->get_positional() == positional && !option->get_group().empty() &&
               (app->get_parent() == nullptr || option != app->get_help_ptr());
    });
}

std::string synopsis_of(const CLI::App* sub) {
    std::string synopsis = sub->get_name();
    for (const CLI::Option* option : visible_options(sub, true)) synopsis += " " + usage_of(option);
    for (const CLI::Option* option : visible_options(sub, false)) {
        synopsis += " " + usage_of(option);
    }
    return synopsis;
}

// An option's entry: its names and value on one line, then what it does and its default.
std::string option_entry(const CLI::Option* option) {
    const std::string head = option->get_positional()
                                 ? option->get_name(true, false)
                                 : option_names(option, ", ") + value_suffix(option);
    std::string text = option->get_description();
    if (!text.empty()) {
        text.front() = static_cast<char>(std::toupper(static_cast<unsigned char>(text.front())));
    }
    if (!text.empty() && text.back() != '.') text += '.';
    if (!option->get_default_str().empty()) text += " Default: " + option->get_default_str() + ".";
    return std::string(body_indent, ' ') + head + "\n" + wrap(text, detail_indent);
}

class ManualFormatter : public CLI::Formatter {
  public:
    std::string make_help(const CLI::App* app, std::string /*name*/,
                          CLI::AppFormatMode /*mode*/) const override {
        return app->get_parent() == nullptr ? program_page(app) : command_page(app);
    }

  private:
    static std::string program_page(const CLI::App* app) {
        std::ostringstream out;
        out << "NAME\n"
            << wrap(app->get_name() + " - command-line client of gimbald, the camera gimbal daemon",
                    body_indent)
            << "\nSYNOPSIS\n"
            << wrap(app->get_name() + " [OPTIONS] COMMAND [ARGUMENTS] [COMMAND OPTIONS]",
                    body_indent)
            << wrap(app->get_name() + " COMMAND --help", body_indent) << "\nDESCRIPTION\n"
            << wrap(app->get_description(), body_indent) << "\nOPTIONS\n";
        for (const CLI::Option* option : visible_options(app, false)) out << option_entry(option);
        out << "\nCOMMANDS\n";
        std::vector<std::string> groups;
        for (const CLI::App* sub : app->get_subcommands({})) {
            if (std::find(groups.begin(), groups.end(), sub->get_group()) == groups.end()) {
                groups.push_back(sub->get_group());
            }
        }
        for (const std::string& group : groups) {
            out << "   " << group << "\n";
            for (const CLI::App* sub : app->get_subcommands({})) {
                if (sub->get_group() != group) continue;
                out << wrap(synopsis_of(sub), body_indent, body_indent + 4)
                    << wrap(sub->get_description(), detail_indent);
            }
        }
        out << "\n" << app->get_footer();
        return out.str();
    }

    static std::string command_page(const CLI::App* sub) {
        const std::string program = sub->get_parent()->get_name();
        std::ostringstream out;
        out << "NAME\n"
            << wrap(program + " " + sub->get_name() + " - " + sub->get_description(), body_indent)
            << "\nSYNOPSIS\n"
            << wrap(program + " [OPTIONS] " + synopsis_of(sub), body_indent, body_indent + 4);
        const auto positionals = visible_options(sub, true);
        if (!positionals.empty()) {
            out << "\nARGUMENTS\n";
            for (const CLI::Option* option : positionals) out << option_entry(option);
        }
        const auto options = visible_options(sub, false);
        if (!options.empty()) {
            out << "\nCOMMAND OPTIONS\n";
            for (const CLI::Option* option : options) out << option_entry(option);
        }
        out << "\n"
            << manual_section("GLOBAL OPTIONS",
                              "--host, --port, --gimbal, --token, --timeout, "
                              "--id, --print-request and --pretty: see " +
                                  program + " --help.");
        if (!sub->get_footer().empty()) out << "\n" << sub->get_footer();
        return out.str();
    }
};

const char* const description =
    "gimbalctl sends one command to the JSON command socket of gimbald (one JSON object per "
    "UDP datagram, section 4 of the gimbald interface contract) and prints the reply as one "
    "line of JSON on standard output.\n"
    "Each COMMAND below is one request: its arguments are the required parameters and its "
    "options the optional ones, in the contract's units (degrees, metres, m/s, seconds, or "
    "milliseconds where the key ends in _ms). An optional parameter that is not given is not "
    "sent, and the daemon applies the default shown. Booleans the contract requires (the "
    "laser's enable, arm and fire) are always sent, as false unless given. Ranges are checked "
    "by the daemon, which answers out_of_range naming the key.\n"
    "The reply is matched to the request by its id (random unless --id is given); any other "
    "datagram is ignored. The watch command subscribes to state and event datagrams, renews "
    "the subscription at half its ttl and prints one JSON line per datagram, like gpspipe.\n"
    "Options may be given before or after the command. gimbalctl COMMAND --help describes a "
    "command.";

std::string examples_section() {
    return "EXAMPLES\n"
           "       Is the daemon there, and which gimbals does it have?\n"
           "           gimbalctl ping && gimbalctl --pretty list\n"
           "\n"
           "       Stare at a point 300 m above the ellipsoid on gimbal \"main\":\n"
           "           gimbalctl --gimbal main geopoint 45.7 -121.5 300 --stare\n"
           "\n"
           "       Scan a two-point path, or look straight down:\n"
           "           gimbalctl path 45.7,-121.5,300 45.71,-121.49,310 --along-step 10\n"
           "           gimbalctl path --down\n"
           "\n"
           "       Pan at 5 deg/s without stabilization; point at pan 30, tilt -45:\n"
           "           gimbalctl rate 5 0 --no-stabilized\n"
           "           gimbalctl position 30 -45 --stabilized\n"
           "\n"
           "       Fire laser 0 (needs laser.allow_fire in the daemon's configuration):\n"
           "           gimbalctl laser --enable --arm --fire --on-ms 100 --off-ms 900\n"
           "\n"
           "       Show the request a command would send, without sending it:\n"
           "           gimbalctl --print-request --id 7 camera-zoom 4.5 --index 1\n"
           "\n"
           "       Any request, typed as JSON, on a daemon that wants a token:\n"
           "           gimbalctl --host gcs.local --token s3cret send '{\"cmd\":\"stare_ack\"}'\n"
           "\n"
           "       The gimbal's latitude in a script:\n"
           "           gimbalctl state | python3 -c 'import json, sys\n"
           "           print(json.load(sys.stdin)[\"state\"][\"telemetry\"][\"lat\"])'\n"
           "\n"
           "       Log state at 2 Hz with events, one JSON object per line, until Ctrl-C:\n"
           "           gimbalctl watch --rate 2 > gimbal.jsonl\n"
           "           gimbalctl watch --count 1 --no-events | jq .state.link\n"
           "\n"
           "       The same socket without gimbalctl, with socat:\n"
           "           echo '{\"cmd\":\"version\",\"id\":1}' | socat -t 2 - UDP:127.0.0.1:8760\n";
}

// "       0      text..." with the text wrapped under itself.
std::string status_entry(const std::string& status, const std::string& text) {
    std::string entry = wrap(text, detail_indent);
    const std::string label = std::string(body_indent, ' ') + status;
    return label + entry.substr(label.size());
}

std::string exit_status_section() {
    return "EXIT STATUS\n" +
           status_entry("0",
                        "The reply said ok:true; or watch ended by --count, SIGINT or SIGTERM; "
                        "or --help, --version or --print-request.") +
           status_entry("1",
                        "The reply said ok:false. \"gimbalctl: CODE: MESSAGE\" is written to "
                        "standard error and the reply to standard output. CODE is one of the "
                        "contract's error codes (bad_request, out_of_range, forbidden, ...).") +
           status_entry("2",
                        "No reply within --timeout, or the host refused the datagram (nothing "
                        "listens on that port), or the host name does not resolve; a message "
                        "on standard error.") +
           status_entry("64",
                        "Usage error: unknown command or option, missing or malformed argument "
                        "(EX_USAGE).");
}

std::string see_also_section() {
    return manual_section("SEE ALSO",
                          "gimbald(8), gimbal-sim(1), docs/gimbalctl.md and the gimbald "
                          "interface contract (JSON commands, units, error codes).");
}

}  // namespace

std::string manual_section(const std::string& title, const std::string& text) {
    return title + "\n" + wrap(text, body_indent);
}

void install_manual(CLI::App& app) {
    app.formatter(std::make_shared<ManualFormatter>());
    app.description(description);
    app.footer(examples_section() + "\n" + exit_status_section() + "\n" + see_also_section());
}

}  // namespace gimbalctl
