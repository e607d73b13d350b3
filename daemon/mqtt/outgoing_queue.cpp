#include "outgoing_queue.hpp"

#include <algorithm>

namespace gimbald::mqtt {

std::size_t OutgoingQueue::make_room() {
    std::size_t dropped = 0;
    while (messages_.size() >= max_) {
        // The oldest message of the most expendable kind present.
        auto victim = messages_.end();
        for (Kind kind : {Kind::state, Kind::retained, Kind::event}) {
            victim = std::find_if(messages_.begin(), messages_.end(),
                                  [kind](const Message& m) { return m.kind == kind; });
            if (victim != messages_.end()) break;
        }
        messages_.erase(victim);
        ++dropped;
    }
    dropped_ += dropped;
    return dropped;
}

std::size_t OutgoingQueue::push(Message message) {
    if (message.kind == Kind::state) {
        auto same = std::find_if(messages_.begin(), messages_.end(), [&](const Message& m) {
            return m.kind == Kind::state && m.topic == message.topic;
        });
        if (same != messages_.end()) {
            // Superseded: the newest STATE takes the older one's place in line.
            *same = std::move(message);
            ++dropped_;
            return 1;
        }
    }
    const std::size_t dropped = make_room();
    messages_.push_back(std::move(message));
    return dropped;
}

std::size_t OutgoingQueue::push_front(Message message) {
    const std::size_t dropped = make_room();
    messages_.push_front(std::move(message));
    return dropped;
}

std::optional<Message> OutgoingQueue::pop() {
    if (messages_.empty()) return std::nullopt;
    Message m = std::move(messages_.front());
    messages_.pop_front();
    return m;
}

}  // namespace gimbald::mqtt
