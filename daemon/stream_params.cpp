#include "stream_params.hpp"

#include "command/result.hpp"
#include "protocols/registry.hpp"
#include "state/messages.hpp"

namespace gimbald {

void read_stream_options(gimbal::command::JsonParams& params, gimbal::state::StreamOptions& out) {
    out.changes = params.boolean_or("changes", false);
    out.full_every_s = params.number_or("full_every_s", 10.0);
    if (const nlohmann::json* k = params.raw("keys")) {
        auto keys = gimbal::state::read_state_keys(*k, gimbal::protocols::is_state_key);
        if (keys)
            out.keys = std::move(keys).value();
        else
            params.fail(keys.error().code, keys.error().message);
    }
}

void describe_stream_options(const gimbal::state::StreamOptions& options, nlohmann::json& results) {
    if (!options.keys.empty()) results["keys"] = options.keys;
    if (!options.changes) return;  // a v2 reply stays as it was
    results["changes"] = true;
    results["full_every_s"] = options.full_every_s;
}

}  // namespace gimbald
