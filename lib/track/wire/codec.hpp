// Encoding and decoding of the gimbald <-> gimbal-track messages (messages.hpp), derived from
// their fields() declarations. Decoding trusts nothing: every read is bounds-checked, numbers
// must be finite and in their declared range, enumerations and booleans must be one of their
// values, lengths are capped, and a datagram must end where its message ends. Encoding
// checks the same rules, so neither side can send what the other would refuse.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "track/wire/messages.hpp"

namespace gimbal::track::wire {

struct Decoded {
    std::optional<Message> message;  // set when the datagram is valid
    std::string error;               // otherwise what is wrong: "box.confidence: out of range"
};

// One datagram -> one message. AccessUnit::bytes views `datagram`: keep it alive.
Decoded decode(std::span<const std::uint8_t> datagram);

// One message -> one datagram, appended to `out` (cleared first). False (and `error` set,
// `out` empty) when the message breaks its declaration (a value out of range, a string too
// long, a box with x1 <= x0, ...).
bool encode(const Message& message, std::vector<std::uint8_t>& out, std::string* error = nullptr);

// The same, for a message type known at compile time; empty on an invalid message.
template <class M>
std::vector<std::uint8_t> encode(const M& message) {
    std::vector<std::uint8_t> out;
    encode(Message{message}, out);
    return out;
}

// The type byte of a datagram without decoding it (nullopt when too short or unknown).
std::optional<MessageType> peek_type(std::span<const std::uint8_t> datagram);

}  // namespace gimbal::track::wire
