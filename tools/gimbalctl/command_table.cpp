#include "command_table.hpp"

#include "command/catalogue.hpp"
#include "manual.hpp"
#include "protocols/registry.hpp"

namespace gimbalctl {

std::string command_group(const std::string& cmd) {
    const auto* spec = gimbal::command::find_command(cmd);
    if (!spec) return group_client;
    if (spec->scope != gimbal::command::Scope::protocol) return group_any;
    const auto planners = gimbal::protocols::planners_of(cmd);
    std::string names;
    for (std::size_t i = 0; i < planners.size(); ++i) {
        if (i > 0) names += i + 1 == planners.size() ? " and " : ", ";
        names += planners[i]->display_name;
    }
    return names + " commands";
}

Command& CommandTable::add(const std::string& name, const std::string& cmd,
                           const std::string& note) {
    const auto* spec = gimbal::command::find_command(cmd);
    std::string description = spec ? std::string(spec->summary) : std::string();
    if (!note.empty()) description += " " + note;
    return add(name, cmd, command_group(cmd), description);
}

Command& CommandTable::add(const std::string& name, const std::string& cmd,
                           const std::string& group, const std::string& description) {
    Command& command = commands_.emplace_back();
    command.cmd = cmd;
    command.app = app_.add_subcommand(name, description);
    command.app->group(group);
    command.params = [] { return Json::object(); };
    if (const auto* spec = gimbal::command::find_command(cmd))
        command.takes_gimbal = spec->scope != gimbal::command::Scope::daemon;
    command.app->footer("");  // not the program page's EXAMPLES, inherited from the parent
    if (!cmd.empty()) {
        command.app->footer(manual_section(
            "REQUEST", "Sends {\"cmd\": \"" + cmd +
                           "\", ...} with the keys named above; add --print-request to see "
                           "the exact object without sending it."));
    }
    return command;
}

const Command* CommandTable::selected() const {
    for (const Command& command : commands_) {
        if (command.app->parsed()) return &command;
    }
    return nullptr;
}

}  // namespace gimbalctl
