// One request, one reply: the default action of every command but watch.
#pragma once

#include "cli.hpp"

namespace gimbalctl {

// Sends the request, waits up to --timeout for the reply carrying its id (other datagrams
// are ignored), prints it and returns the exit status.
int run_exchange(const GlobalOptions& globals, const Json& request);

}  // namespace gimbalctl
