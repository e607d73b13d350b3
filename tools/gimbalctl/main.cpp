// gimbalctl: command-line client of gimbald's JSON command socket. See `gimbalctl --help`
// and docs/gimbalctl.md.
#include "cli.hpp"
#include "exchange.hpp"
#include "exit_status.hpp"
#include "mqtt_run.hpp"
#include "output.hpp"
#include "signing.hpp"
#include "watch.hpp"

int main(int argc, char** argv) {
    using namespace gimbalctl;
    const ParseResult parsed = parse_command_line(argc, argv);
    if (!parsed.invocation) return parsed.exit_status;
    const Invocation& invocation = *parsed.invocation;

    if (invocation.action == Action::keygen) return run_keygen(invocation.request.at("file"));
    if (invocation.global.print_request) {
        print_json(invocation.request, invocation.global.pretty);
        return exit_ok;
    }
    if (invocation.global.mqtt) {
        if (invocation.action == Action::watch)
            return run_mqtt_watch(invocation.global, invocation.request, invocation.watch_count);
        return run_mqtt_exchange(invocation.global, invocation.request);
    }
    if (invocation.action == Action::watch) {
        return run_watch(invocation.global, invocation.request, invocation.watch_count);
    }
    return run_exchange(invocation.global, invocation.request);
}
