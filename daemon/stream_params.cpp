#include "stream_params.hpp"

#include "command/result.hpp"
#include "state/messages.hpp"

namespace gimbald {

void read_stream_options(gimbal::command::Params& params, gimbal::state::StreamOptions& out) {
    out.changes = params.boolean_or("changes", false);
    out.full_every_s = params.number_or("full_every_s", 1.0, 3600.0, 10.0);
    if (const nlohmann::json* k = params.raw("keys")) {
        if (auto problem = gimbal::state::parse_state_keys(*k, out.keys); !problem.empty())
            params.fail(gimbal::command::code::bad_request, problem);
    }
}

void describe_stream_options(const gimbal::state::StreamOptions& options, nlohmann::json& results) {
    if (!options.keys.empty()) results["keys"] = options.keys;
    if (!options.changes) return;  // a v2 reply stays as it was
    results["changes"] = true;
    results["full_every_s"] = options.full_every_s;
}

}  // namespace gimbald
