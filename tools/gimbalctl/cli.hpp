// The command line: global options, the sub-commands, and the request they describe.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "command_table.hpp"
#include "json_types.hpp"
#include "mqtt_options.hpp"

namespace gimbalctl {

struct GlobalOptions {
    std::string host = "127.0.0.1";
    std::uint16_t port = 8760;
    std::optional<std::string> gimbal;
    std::optional<std::string> token;
    std::optional<std::string> key_file;  // --key-file and --key-id: sign every request
    std::optional<std::string> key_id;
    double timeout_s = 2.0;
    bool print_request = false;
    bool pretty = false;
    std::optional<MqttTarget> mqtt;  // --mqtt: through a broker instead of UDP
};

// What to do after a successful parse.
struct Invocation {
    GlobalOptions global;
    Json request;  // complete: cmd, id, gimbal, token, parameters
    Action action = Action::exchange;
    std::int64_t watch_count = 0;  // watch: stop after this many datagrams; 0 = never
};

// Either an invocation, or the exit status when parsing ended the program (help: 0, usage
// error: 64, with CLI11's message already printed).
struct ParseResult {
    std::optional<Invocation> invocation;
    int exit_status = 0;
};

ParseResult parse_command_line(int argc, char** argv);

// The "id" to send: --id as typed (a whole number becomes a JSON number), else a random one.
Json request_id(const std::optional<std::string>& id_option);

}  // namespace gimbalctl
