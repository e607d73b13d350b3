// Section 4.1 of the interface contract: commands every gimbal (or the daemon) answers; and
// section 17's `klv` (the latest KLV set of a gimbal's video).
#include <memory>

#include "command_table.hpp"
#include "params.hpp"

namespace gimbalctl {

void add_common_commands(CommandTable& table) {
    Command& ping =
        table.add("ping", "ping", group_any, "Check that gimbald answers; replies \"pong\": true.");
    ping.takes_gimbal = false;

    Command& version = table.add("version", "version", group_any,
                                 "The daemon's version and the protocols it speaks.");
    version.takes_gimbal = false;

    Command& list = table.add("list", "list", group_any,
                              "The configured gimbals with their protocol and link state.");
    list.takes_gimbal = false;

    Command& state = table.add(
        "state", "state", group_any,
        "The STATE object of one gimbal (telemetry, link counters, ...), whole or --keys.");
    auto p = std::make_shared<Params>(state.app);
    state.params = [p] { return p->json(); };
    p->names("--keys", "keys",
             "only these top-level STATE keys (protocol, link and stale always come), e.g. "
             "--keys telemetry,gps")
        ->default_str("every key");

    table.add("klv", "klv");  // group and summary from the catalogue
}

}  // namespace gimbalctl
