// The datagrams every stream shares (contract section 4.1): STATE and event messages, and
// STATE restricted to the top-level keys a subscriber asked for (`subscribe.keys`).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "command/result.hpp"
#include "state/event.hpp"

namespace gimbal::state {

// {"type":"state","gimbal":NAME,"state":STATE}
nlohmann::json state_message(const std::string& gimbal, nlohmann::json state);
// {"type":"event","gimbal":NAME,"event":KIND, ...fields}
nlohmann::json event_message(const std::string& gimbal, const Event& event);

// What a subscriber gets in place of a push too large for one datagram (contract section 14,
// v4; docs/json-api.md): {"type":"event","gimbal":NAME,"event":"too_large","bytes":N,
// "limit":L,"largest":{KEY:BYTES,...},"message":TEXT}, `largest` naming the (at most three)
// largest top-level members of `body`, what the push carried (a STATE, a patch, an event),
// with their size as JSON text, so the subscriber can leave them out with `keys`.
nlohmann::json too_large_event(const std::string& gimbal, std::size_t bytes, std::size_t limit,
                               const nlohmann::json& body);

// True for a top-level STATE key every gimbal may have, whatever its protocol (`telemetry`,
// `lasers`, `vehicle`, `record`, ...). A protocol's own keys are declared by its registry entry;
// protocols::is_state_key knows both.
bool is_shared_state_key(std::string_view key);
// STATE restricted to `keys`; `protocol`, `link` and `stale` are always kept. An empty list
// keeps everything.
nlohmann::json select_keys(const nlohmann::json& state, const std::vector<std::string>& keys);

// Reads a `keys` parameter: an array of STATE key names that `is_known` knows (repeats
// dropped), or bad_request naming the problem. The daemon passes protocols::is_state_key.
command::Result<std::vector<std::string>> read_state_keys(
    const nlohmann::json& value,
    const std::function<bool(std::string_view)>& is_known = is_shared_state_key);

}  // namespace gimbal::state
