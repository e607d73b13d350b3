// The one command catalogue (contract section 4): every command's name, who answers it, the
// role it needs, whether it needs the command token, and its parameters (names, types,
// ranges, defaults). The request path's known-command check, the roles, the envelope's
// is_*_command, gimbalctl's help groups and the command tables of docs/json-api.md are
// derived from it. Which protocols plan a protocol command is the protocol registry's to say
// (lib/protocols): each protocol lists the catalogue commands it plans.
//
// A request's parameters are checked against this table once, when the request is read
// (command/request.hpp): ranges are declared here and nowhere else. tests/unit/protocols
// checks that every planner accepts and refuses exactly what this table says.
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace gimbal::command {

// Who answers a command.
enum class Scope {
    daemon,        // the daemon itself; takes no `gimbal` (ping, version, list)
    every_gimbal,  // any gimbal, whatever its protocol (state, subscribe, unsubscribe)
    protocol,      // the gimbal's protocol plans it, if that protocol has it
};

// The role a signed request needs (contract section 10).
enum class Access {
    open,  // none: every allowed source
    observe,
    control,
    laser_when_firing,  // `laser` unless the request holds an explicit `fire: false`
};

enum class ParamType {
    number,   // JSON number within [min, max]
    integer,  // whole JSON number within [min, max]
    boolean,
    text,     // printable ASCII string of at most max characters
    choice,   // one of `choices`
    numbers,  // array of exactly `count` numbers, each within [min, max]
    points,   // array of 1..max {"lat","lon","alt"} objects
    keys,     // array of top-level STATE key names
};

struct ParamSpec {
    std::string_view name = {};
    ParamType type = ParamType::number;
    bool required = false;
    double min = 0;              // number, integer, numbers; text: unused
    double max = 0;              // number, integer, numbers; text: longest; points: most points
    std::string_view unit = {};  // "deg", "m", "s", "ms", "deg/s", "m/s", or empty
    std::string_view default_text = {};  // as a person reads it ("0", "wgs84", "now"); empty: none
    std::span<const std::string_view> choices = {};
    std::size_t count = 0;                   // numbers
    std::string_view note = {};              // anything the columns above cannot say
    std::span<const ParamSpec> fields = {};  // points: the fields of each point
};

struct CommandSpec {
    std::string_view name = {};
    Scope scope = Scope::protocol;
    Access access = Access::control;
    bool needs_token = true;        // command.token applies (not to ping, version, list, state)
    std::string_view summary = {};  // one sentence: gimbalctl's help, the docs
    std::span<const ParamSpec> params = {};
    std::string_view rule = {};   // a rule across parameters ("yaw_deg and/or pitch_deg"), or empty
    std::string_view reply = {};  // what the reply adds (commands the daemon answers itself)
    std::string_view example = {};  // the parameters of one valid request, as a JSON object text
};

// Every command, in the contract's order: section 4.1, the ground and image commands of
// sections 15 and 16, then the protocol commands.
std::span<const CommandSpec> catalogue();
const CommandSpec* find_command(std::string_view name);
bool is_known_command(std::string_view name);
const ParamSpec* find_param(const CommandSpec& command, std::string_view name);

std::string_view to_string(Scope scope);
std::string_view to_string(Access access);
std::string_view to_string(ParamType type);

}  // namespace gimbal::command
