// gimbalctl over MQTT: one request published to `{prefix}/{station}/cmd` with an MQTT 5
// response topic and correlation data, its reply awaited there; or `watch` of the retained
// STATE and the events one station (or every station: "+") publishes.
#pragma once

#include <cstdint>

#include "cli.hpp"

namespace gimbalctl {

// Exit statuses as for UDP: 0 ok reply, 1 error reply, 2 no reply (or no broker) in time.
int run_mqtt_exchange(const GlobalOptions& globals, const Json& request);
// Prints {"type":"state","station","gimbal","state"} and event lines (with "station") until
// SIGINT/SIGTERM or `count` lines. `subscribe` supplies gimbal, events and keys.
int run_mqtt_watch(const GlobalOptions& globals, const Json& subscribe, std::int64_t count);

}  // namespace gimbalctl
