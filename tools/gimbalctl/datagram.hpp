// Classifying what arrives on the socket: our reply, a subscription datagram, or noise.
#pragma once

#include <optional>
#include <string_view>

#include "json_types.hpp"

namespace gimbalctl {

// The datagram as a JSON object; nullopt for anything else (ignored as stray).
std::optional<Json> parse_datagram(std::string_view datagram);

// A reply carries the request's id unchanged; anything else is someone else's, except a
// too_large or bad_json refusal with a null id (the daemon did not read the request).
bool is_reply_to(const Json& datagram, const Json& request);

// State and event datagrams of a subscription carry "type" and are not replies.
bool is_subscription_datagram(const Json& datagram);

}  // namespace gimbalctl
