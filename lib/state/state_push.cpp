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

const json& PushMessage::json() const {
    if (!json_)
        json_ = full_ ? delta_message(gimbal_, *full_, *body_) : state_message(gimbal_, *body_);
    return *json_;
}

const std::shared_ptr<const std::string>& PushMessage::text() const {
    if (text_) return text_;
    // Written out rather than dumped from json(): that would copy the whole STATE first.
    const std::string body = dump_message(*body_);
    const std::string name = dump_message(nlohmann::json(gimbal_));
    std::string text;
    text.reserve(body.size() + name.size() + 48);
    text += '{';
    if (full_) text += *full_ ? "\"full\":true," : "\"full\":false,";
    text += "\"gimbal\":" + name + ",\"state\":" + body + ",\"type\":\"state\"}";
    text_ = std::make_shared<const std::string>(std::move(text));
    return text_;
}

PushBatch::PushBatch(std::string gimbal, json state)
    : gimbal_(std::move(gimbal)), state_(std::make_shared<const json>(std::move(state))) {}

const std::shared_ptr<const json>& PushBatch::selected(const std::vector<std::string>& keys) {
    auto& slot = selected_[keys];
    if (!slot)
        slot = keys.empty() ? state_ : std::make_shared<const json>(select_keys(*state_, keys));
    return slot;
}

const PushMessage& PushBatch::next(const StreamOptions& options, DeltaCursor& cursor,
                                   double now_s) {
    const auto& current = selected(options.keys);
    if (!options.changes) {
        const Key key{options.keys, Kind::plain, nullptr};
        auto it = messages_.find(key);
        if (it == messages_.end())
            it = messages_.emplace(key, PushMessage(gimbal_, std::nullopt, current)).first;
        return it->second;
    }
    const bool full = cursor.full_due(now_s);
    const json* previous = full ? nullptr : cursor.last().get();
    const Key key{options.keys, full ? Kind::full : Kind::patch, previous};
    auto it = messages_.find(key);
    if (it == messages_.end()) {
        if (!full) pinned_.push_back(cursor.last());
        auto body =
            full ? current : std::make_shared<const json>(merge_patch_diff(*previous, *current));
        it = messages_.emplace(key, PushMessage(gimbal_, full, std::move(body))).first;
    }
    cursor.pushed(current, full, now_s, options.full_every_s);
    return it->second;
}

const std::vector<PushMessage>& PushBatch::split(const PushMessage& message, std::size_t budget) {
    auto& parts = parts_[&message];
    if (!parts.empty()) return parts;
    if (message.full() != false || message.text()->size() <= budget) {
        parts.push_back(message);
        return parts;
    }
    // The room for the patch is the budget less the message around it.
    const std::size_t around = message.text()->size() - dump_message(*message.body()).size();
    for (auto& part : split_patch(*message.body(), budget > around ? budget - around : 0))
        parts.emplace_back(gimbal_, false, std::make_shared<const json>(std::move(part)));
    return parts;
}

json delta_message(const std::string& gimbal, bool full, json state) {
    return {{"type", "state"}, {"gimbal", gimbal}, {"full", full}, {"state", std::move(state)}};
}

std::string dump_message(const json& message) {
    return message.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace gimbal::state
