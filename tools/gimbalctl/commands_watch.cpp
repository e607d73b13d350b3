// `watch`: the subscribe request of section 4.1, plus the client-side --count.
#include <memory>

#include <CLI/CLI.hpp>

#include "command_table.hpp"
#include "manual.hpp"
#include "numbers.hpp"
#include "params.hpp"

namespace gimbalctl {

void add_watch_command(CommandTable& table, std::int64_t& count) {
    Command& command =
        table.add("watch", "subscribe", group_client,
                  "Subscribe and print each state and event datagram as one JSON line until "
                  "interrupted (SIGINT/SIGTERM: unsubscribe, exit 0) or --count datagrams.");
    command.action = Action::watch;
    auto p = std::make_shared<Params>(command.app);
    command.params = [p] { return p->json(); };
    p->number("--rate", "rate_hz", "state datagrams per second (0.1..50)")
        ->type_name("HZ")
        ->default_str("10");
    p->number("--ttl", "ttl_s",
              "subscription lifetime, seconds (1..3600); gimbalctl renews it every ttl/2")
        ->type_name("S")
        ->default_str("60");
    p->flag("--events,!--no-events", "events", "also print event datagrams, or not")
        ->default_str("events on");
    p->flag("--changes", "changes",
            "delta stream (subscribe changes: true): the daemon sends a full STATE every "
            "--full-every seconds and only what changed in between; watch merges them and "
            "prints the whole STATE each time")
        ->default_str("off");
    p->number("--full-every", "full_every_s",
              "with --changes: seconds between full STATEs (1..3600)")
        ->type_name("S")
        ->default_str("10");
    p->names("--keys", "keys",
             "only these top-level STATE keys (protocol, link and stale always come), e.g. "
             "--keys telemetry,lasers")
        ->default_str("every key");
    command.app->add_option("--count", count, "exit 0 after printing this many datagrams")
        ->type_name("N")
        ->check(count_check())
        ->default_str("none, until interrupted");
    command.app->footer(manual_section(
        "REQUEST",
        "Sends {\"cmd\": \"subscribe\", ...} with the keys named above, again every ttl/2, "
        "and {\"cmd\": \"unsubscribe\"} when it stops. Replies to these are not printed; an "
        "error reply to the first subscribe ends watch with status 1, no reply with status "
        "2. With --changes every state line still holds the whole STATE, merged from the "
        "pushes (JSON Merge Patch, RFC 7396); its \"full\" says whether the daemon sent it "
        "whole. Patches that arrive before the first full STATE are not printed."));
}

}  // namespace gimbalctl
