// The STATE stream parameters of `subscribe`, shared by the UDP command socket and the
// WebSocket stream (contract sections 4.1 and 14): `keys`, `changes`, `full_every_s`.
#pragma once

#include <nlohmann/json.hpp>

#include "command/params.hpp"
#include "state/state_push.hpp"

namespace gimbald {

// Reads the parameters into `out`; a problem is left in `params` (bad_request or
// out_of_range naming the key).
void read_stream_options(gimbal::command::JsonParams& params, gimbal::state::StreamOptions& out);

// Adds what the subscriber got to a subscribe reply: `keys` when restricted, `changes` and
// `full_every_s` when changes are on.
void describe_stream_options(const gimbal::state::StreamOptions& options, nlohmann::json& results);

}  // namespace gimbald
