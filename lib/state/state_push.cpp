#include "state/state_push.hpp"

#include "state/merge_patch.hpp"
#include "state/messages.hpp"

namespace gimbal::state {

using nlohmann::json;

void DeltaCursor::pushed(std::shared_ptr<const json> state, bool full, double now_s,
                         double full_every_s) {
    last_ = std::move(state);
    if (full) next_full_s_ = now_s + full_every_s;
}

const std::shared_ptr<const std::string>& PushMessage::text() const {
    if (!text_) text_ = std::make_shared<const std::string>(dump_message(message_));
    return text_;
}

PushBatch::PushBatch(std::string gimbal, json state)
    : gimbal_(std::move(gimbal)), state_(std::move(state)) {}

const std::shared_ptr<const json>& PushBatch::selected(const std::vector<std::string>& keys) {
    auto& slot = selected_[keys];
    if (!slot) slot = std::make_shared<const json>(select_keys(state_, keys));
    return slot;
}

const PushMessage& PushBatch::next(const StreamOptions& options, DeltaCursor& cursor,
                                   double now_s) {
    const auto& current = selected(options.keys);
    if (!options.changes) {
        const Key key{options.keys, Kind::plain, nullptr};
        auto it = messages_.find(key);
        if (it == messages_.end())
            it = messages_.emplace(key, PushMessage(state_message(gimbal_, *current))).first;
        return it->second;
    }
    const bool full = cursor.full_due(now_s);
    const json* previous = full ? nullptr : cursor.last().get();
    const Key key{options.keys, full ? Kind::full : Kind::patch, previous};
    auto it = messages_.find(key);
    if (it == messages_.end()) {
        if (!full) pinned_.push_back(cursor.last());
        json body = full ? *current : merge_patch_diff(*previous, *current);
        it = messages_.emplace(key, PushMessage(delta_message(gimbal_, full, std::move(body))))
                 .first;
    }
    cursor.pushed(current, full, now_s, options.full_every_s);
    return it->second;
}

json delta_message(const std::string& gimbal, bool full, json state) {
    return {{"type", "state"}, {"gimbal", gimbal}, {"full", full}, {"state", std::move(state)}};
}

std::string dump_message(const json& message) {
    return message.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace gimbal::state
