#include "command_table.hpp"

#include "manual.hpp"

namespace gimbalctl {

Command& CommandTable::add(const std::string& name, const std::string& cmd,
                           const std::string& group, const std::string& description) {
    Command& command = commands_.emplace_back();
    command.cmd = cmd;
    command.app = app_.add_subcommand(name, description);
    command.app->group(group);
    command.params = [] { return Json::object(); };
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
