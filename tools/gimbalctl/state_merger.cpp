#include "state_merger.hpp"

#include "state/merge_patch.hpp"

namespace gimbalctl {

std::optional<Json> StateMerger::merge(const std::string& stream, Json message) {
    const auto full = message.find("full");
    const auto state = message.find("state");
    if (message.value("type", "") != "state" || full == message.end() || !full->is_boolean() ||
        state == message.end())
        return message;
    // The daemon's own JSON type: the merge is lib/state's RFC 7396 code.
    nlohmann::json incoming = nlohmann::json::parse(state->dump());
    if (full->get<bool>()) {
        states_[stream] = std::move(incoming);
    } else {
        const auto held = states_.find(stream);
        if (held == states_.end()) return std::nullopt;
        gimbal::state::merge_patch_apply(held->second, incoming);
    }
    *state = Json::parse(states_[stream].dump());
    return message;
}

}  // namespace gimbalctl
