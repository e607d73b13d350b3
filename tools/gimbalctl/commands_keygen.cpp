// `keygen FILE`: a new command key's secret file (contract section 10). Nothing is sent.
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "command_table.hpp"

namespace gimbalctl {

void add_keygen_command(CommandTable& table) {
    Command& keygen = table.add(
        "keygen", "", group_client,
        "Write a new secret for command.keys to FILE: 32 random bytes as 64 hex characters, "
        "mode 0600. Refuses to overwrite an existing file. Sends nothing.");
    auto file = std::make_shared<std::string>();
    keygen.app->add_option("FILE", *file, "where to write the secret")->required();
    keygen.takes_gimbal = false;
    keygen.action = Action::keygen;
    keygen.params = [file] { return Json{{"file", *file}}; };
}

}  // namespace gimbalctl
