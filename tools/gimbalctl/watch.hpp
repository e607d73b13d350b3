// `gimbalctl watch`: subscribe, keep the subscription alive, print what it delivers.
#pragma once

#include <cstdint>

#include "cli.hpp"

namespace gimbalctl {

// `subscribe` is the complete subscribe request. Prints one JSON line per state or event
// datagram until SIGINT/SIGTERM or `count` lines (0: no limit), then unsubscribes. Returns
// the exit status: 0 on a normal end, 1 when the first subscribe is refused with an error
// reply, 2 when it gets no reply (nor any datagram) within --timeout.
int run_watch(const GlobalOptions& globals, const Json& subscribe, std::int64_t count);

}  // namespace gimbalctl
