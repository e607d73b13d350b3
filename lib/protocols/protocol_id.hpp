// The gimbal protocols gimbald speaks: the one enumeration of them. Everything else about a
// protocol is its registry entry (protocols/registry.hpp). A `switch` over ProtocolId has no
// `default`, so the compiler names every place a new protocol must fill.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace gimbal::protocols {

enum class ProtocolId { orion, viewpro, mavlink, siyi };

// Every protocol, in the order `version` and the docs list them.
inline constexpr std::array all_protocol_ids{ProtocolId::orion, ProtocolId::viewpro,
                                             ProtocolId::mavlink, ProtocolId::siyi};

// The protocol's name in configuration, STATE `protocol` and recordings.
std::string_view to_string(ProtocolId id);
std::optional<ProtocolId> parse_protocol(std::string_view name);

}  // namespace gimbal::protocols
