// `send`: any request object typed by hand, for commands or parameters gimbalctl has no
// sub-command for. The envelope options are added only where the object has no such key.
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "command_table.hpp"

namespace gimbalctl {
namespace {

CLI::Validator json_object_check() {
    return CLI::Validator(
        [](const std::string& text) {
            const Json value = Json::parse(text, nullptr, false);
            if (value.is_discarded()) return std::string("not valid JSON: ") + text;
            if (!value.is_object()) return std::string("not a JSON object: ") + text;
            return std::string{};
        },
        "JSON");
}

}  // namespace

void add_send_command(CommandTable& table) {
    Command& send =
        table.add("send", "", group_client,
                  "Send one raw JSON request object; --gimbal/--token/--id are added only when the "
                  "object has no such key.");
    auto text = std::make_shared<std::string>();
    send.app->add_option("JSON", *text, "the request object, e.g. '{\"cmd\":\"ping\"}'")
        ->required()
        ->check(json_object_check());
    send.raw = true;
    send.params = [text] { return Json::parse(*text); };
}

}  // namespace gimbalctl
