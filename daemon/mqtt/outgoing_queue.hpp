// The bounded queue of MQTT messages waiting for the broker (contract section 9): at most
// `max` messages; when full, the oldest STATE goes first, then the oldest retained
// status/link message, and events and replies last. A STATE for a topic that already has one
// waiting replaces it (only the newest STATE matters). Pure: no I/O.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

namespace gimbald::mqtt {

enum class Kind {
    state,     // P/{gimbal}/state: dropped first
    retained,  // P/status, P/{gimbal}/link
    event,     // P/{gimbal}/event, replies: dropped last
};

struct Message {
    Kind kind = Kind::event;
    std::string topic;
    std::string payload;
    int qos = 0;
    bool retain = false;
    std::optional<std::string> correlation;  // MQTT 5 Correlation Data of a reply
};

class OutgoingQueue {
  public:
    explicit OutgoingQueue(std::size_t max) : max_(max < 1 ? 1 : max) {}

    // Adds a message; returns how many messages were dropped (or replaced) to make room.
    std::size_t push(Message message);
    // Puts a message back at the front (it was handed to the broker connection but not
    // confirmed when the connection broke); may drop others like push().
    std::size_t push_front(Message message);
    std::optional<Message> pop();

    std::size_t size() const { return messages_.size(); }
    bool empty() const { return messages_.empty(); }
    std::uint64_t dropped() const { return dropped_; }
    std::size_t max() const { return max_; }

  private:
    std::size_t make_room();

    std::size_t max_;
    std::deque<Message> messages_;
    std::uint64_t dropped_ = 0;
};

}  // namespace gimbald::mqtt
