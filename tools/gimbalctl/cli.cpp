#include "cli.hpp"

#include <CLI/CLI.hpp>

#include "exit_status.hpp"
#include "manual.hpp"
#include "numbers.hpp"
#include "output.hpp"

namespace gimbalctl {
namespace {

struct RawGlobals {
    GlobalOptions values;
    std::string gimbal;
    std::string token;
    std::string id;
    std::string key_file;
    std::string key_id;
    CLI::Option* key_file_option = nullptr;
    CLI::Option* key_id_option = nullptr;
    CLI::Option* gimbal_option = nullptr;
    CLI::Option* token_option = nullptr;
    CLI::Option* id_option = nullptr;
    MqttOptionsRaw mqtt;
};

void add_global_options(CLI::App& app, RawGlobals& raw) {
    app.set_help_flag("-h,--help",
                      "print this manual, or after a COMMAND that command's page, and exit");
    app.set_version_flag("--version", std::string("gimbalctl ") + GIMBALD_VERSION,
                         "print the version of gimbalctl and exit");
    app.add_option("--host", raw.values.host,
                   "address of gimbald's command socket: IPv4, IPv6 or host name (every "
                   "address the name resolves to is tried in turn while they refuse)")
        ->type_name("HOST")
        ->default_str("127.0.0.1");
    app.add_option("--port", raw.values.port, "UDP port of the command socket")
        ->type_name("PORT")
        ->check(CLI::Range(1, 65535))
        ->default_str("8760");
    raw.gimbal_option =
        app.add_option("--gimbal", raw.gimbal,
                       "gimbal to command (JSON \"gimbal\"); may be left out when the daemon "
                       "has exactly one; never sent with ping, version and list")
            ->type_name("NAME")
            ->default_str("not sent");
    raw.token_option =
        app.add_option("--token", raw.token,
                       "command token (JSON \"token\"), needed when the daemon's command.token "
                       "is set")
            ->type_name("TOKEN")
            ->default_str("not sent");
    raw.key_file_option =
        app.add_option("--key-file", raw.key_file,
                       "sign every request with the secret in FILE (contract section 10; "
                       "make one with `gimbalctl keygen FILE`); replies and subscription "
                       "datagrams must then carry a valid signature of the same key, else "
                       "exit 2 \"unauthenticated reply\". Needs --key-id")
            ->type_name("FILE")
            ->default_str("requests are not signed");
    raw.key_id_option =
        app.add_option("--key-id", raw.key_id, "the id of that key in the daemon's command.keys")
            ->type_name("ID")
            ->needs(raw.key_file_option);
    raw.key_file_option->needs(raw.key_id_option);
    app.add_option("--timeout", raw.values.timeout_s, "seconds to wait for the reply")
        ->type_name("S")
        ->check(positive_check())
        ->default_str("2");
    raw.id_option = app.add_option("--id", raw.id,
                                   "request id (JSON \"id\"), echoed in the reply; a whole "
                                   "number is sent as a JSON number, anything else as a string")
                        ->type_name("ID")
                        ->default_str("random, \"gimbalctl-\" and 8 hex digits");
    app.add_flag("--print-request", raw.values.print_request,
                 "print the request JSON and exit 0 without sending it")
        ->default_str("off");
    app.add_flag("--pretty", raw.values.pretty, "indent the JSON output")->default_str("off");
    add_mqtt_options(app, raw.mqtt);
}

GlobalOptions finish_globals(const RawGlobals& raw) {
    GlobalOptions globals = raw.values;
    if (raw.gimbal_option->count() > 0) globals.gimbal = raw.gimbal;
    if (raw.token_option->count() > 0) globals.token = raw.token;
    if (raw.key_file_option->count() > 0) globals.key_file = raw.key_file;
    if (raw.key_id_option->count() > 0) globals.key_id = raw.key_id;
    return globals;
}

// cmd, id, gimbal, token, then the parameters; `send` keeps its object and fills gaps only.
Json make_request(const Command& command, const GlobalOptions& globals, const Json& id) {
    Json params = command.params();
    if (command.raw) {
        if (!params.contains("id")) params["id"] = id;
        if (globals.gimbal && !params.contains("gimbal")) params["gimbal"] = *globals.gimbal;
        if (globals.token && !params.contains("token")) params["token"] = *globals.token;
        return params;
    }
    Json request = {{"cmd", command.cmd}, {"id", id}};
    if (globals.gimbal && command.takes_gimbal) request["gimbal"] = *globals.gimbal;
    if (globals.token) request["token"] = *globals.token;
    for (auto& [key, value] : params.items()) request[key] = value;
    return request;
}

// A usage error as one `gimbalctl: ` line naming what is wrong and where to read more: an
// unknown command by its name, a bad argument with CLI11's message and the command's help.
std::string usage_problem(const CLI::App& app, const CommandTable& table,
                          const CLI::ParseError& error) {
    if (const Command* command = table.selected())
        return std::string(error.what()) + " (see gimbalctl " + command->app->get_name() +
               " --help)";
    // No command was recognised: the first word left over is what was meant as one.
    for (const auto& word : app.remaining())
        if (!word.empty() && word.front() != '-')
            return "unknown command '" + word + "' (gimbalctl --help lists the commands)";
    if (dynamic_cast<const CLI::RequiredError*>(&error) != nullptr && app.get_subcommands().empty())
        return "a COMMAND is required (gimbalctl --help lists the commands)";
    return std::string(error.what()) + " (see gimbalctl --help)";
}

}  // namespace

ParseResult parse_command_line(int argc, char** argv) {
    CLI::App app("", "gimbalctl");
    install_manual(app);
    app.fallthrough();  // global options may follow the command
    app.require_subcommand(1);

    RawGlobals raw;
    add_global_options(app, raw);
    std::int64_t watch_count = 0;
    CommandTable table(app);
    add_common_commands(table);
    add_ground_commands(table);
    add_track_commands(table);
    add_gimbal_commands(table);
    add_watch_command(table, watch_count);
    add_send_command(table);
    add_keygen_command(table);

    try {
        app.parse(argc, argv);
        const Command* command = table.selected();
        if (command == nullptr) throw CLI::RequiredError("a COMMAND is required");
        Invocation invocation;
        invocation.global = finish_globals(raw);
        invocation.global.mqtt = finish_mqtt_options(app, raw.mqtt);
        const std::optional<std::string> id =
            raw.id_option->count() > 0 ? std::optional<std::string>(raw.id) : std::nullopt;
        invocation.request = make_request(*command, invocation.global, request_id(id));
        invocation.action = command->action;
        invocation.watch_count = watch_count;
        return ParseResult{std::move(invocation), exit_ok};
    } catch (const CLI::ParseError& error) {
        // --help and --version print to stdout and exit 0, as CLI11 does.
        if (error.get_exit_code() == 0) return ParseResult{std::nullopt, app.exit(error)};
        print_diagnostic(usage_problem(app, table, error));
        return ParseResult{std::nullopt, exit_usage};
    }
}

}  // namespace gimbalctl
