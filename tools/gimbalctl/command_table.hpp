// The sub-commands of gimbalctl: each one is a CLI11 sub-app plus a function that turns the
// parsed arguments into the parameters of one JSON request.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "json_types.hpp"

namespace gimbalctl {

enum class Action {
    exchange,  // send one request, print its reply
    watch,     // subscribe and print state/event datagrams
    keygen,    // write a new secret file; nothing is sent
};

struct Command {
    std::string cmd;  // JSON "cmd" value, e.g. "camera_switch"
    CLI::App* app = nullptr;
    std::function<Json()> params;  // parameters of the request (without cmd/id/gimbal/token)
    bool takes_gimbal = true;      // ping, version and list carry no "gimbal"
    bool raw = false;              // `send`: params() is the whole request object
    Action action = Action::exchange;
};

// Groups shown under COMMANDS in --help: the catalogue's commands for every gimbal, one group
// per set of protocols that plan a command ("<Display name> commands"), then gimbalctl's own.
inline constexpr const char* group_any = "Commands for every gimbal";
inline constexpr const char* group_client = "Client commands";

// The help group of catalogue command `cmd`, from the catalogue and the protocol registry.
std::string command_group(const std::string& cmd);

class CommandTable {
  public:
    explicit CommandTable(CLI::App& app) : app_(app) {}

    // Adds sub-command `name` sending cmd `cmd`; fill in params (and flags) on the result.
    Command& add(const std::string& name, const std::string& cmd, const std::string& group,
                 const std::string& description);
    // The same for catalogue command `cmd`: its group and summary (plus `note`) come from the
    // catalogue.
    Command& add(const std::string& name, const std::string& cmd, const std::string& note = "");

    // The sub-command given on the command line, or nullptr.
    const Command* selected() const;

  private:
    CLI::App& app_;
    std::deque<Command> commands_;  // deque: references stay valid as commands are added
};

// Registration of the sub-commands, one function per section of the interface contract.
void add_common_commands(CommandTable& table);  // 4.1: ping, version, list, state; 17: klv
void add_ground_commands(CommandTable& table);  // 15, 16: elevation, locate, point, project
void add_track_commands(CommandTable& table);   // 20: track, track-stop
void add_gimbal_commands(CommandTable& table);  // the protocols' commands
void add_send_command(CommandTable& table);     // raw JSON
void add_keygen_command(CommandTable& table);   // keygen FILE
// subscribe/unsubscribe; `count` receives --count (0 when not given).
void add_watch_command(CommandTable& table, std::int64_t& count);

}  // namespace gimbalctl
