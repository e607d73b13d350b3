// Every OrionPublic packet with a layout, and dispatch from a packet id to its type.
#pragma once

#include <cstdint>
#include <string_view>
#include <type_traits>

#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/codec/packets_config.hpp"
#include "protocols/orion/codec/packets_control.hpp"
#include "protocols/orion/codec/packets_external.hpp"
#include "protocols/orion/codec/packets_telemetry.hpp"
#include "protocols/orion/codec/packets_version.hpp"

namespace gimbal::orion {

template <class... L>
struct Concat;
template <class... A>
struct Concat<PacketList<A...>> {
    using type = PacketList<A...>;
};
template <class... A, class... B, class... Rest>
struct Concat<PacketList<A...>, PacketList<B...>, Rest...> {
    using type = typename Concat<PacketList<A..., B...>, Rest...>::type;
};

using AllPackets =
    Concat<TelemetryPackets, ControlPackets, ConfigPackets, VersionPackets, ExternalPackets>::type;

// Calls f.template operator()<P>() for the packet type P whose id is `id`.
// Returns false when no packet with a layout has that id.
template <class F, class... P>
bool dispatch_in(PacketList<P...>, std::uint8_t id, F&& f) {
    return ((P::id == id ? (f.template operator()<P>(), true) : false) || ...);
}

template <class F>
bool dispatch(std::uint8_t id, F&& f) {
    return dispatch_in(AllPackets{}, id, std::forward<F>(f));
}

// Calls f.template operator()<P>() for every packet type.
template <class F, class... P>
void for_each_packet_in(PacketList<P...>, F&& f) {
    (f.template operator()<P>(), ...);
}

template <class F>
void for_each_packet(F&& f) {
    for_each_packet_in(AllPackets{}, std::forward<F>(f));
}

// Snake-case name of a packet id ("geolocate_telemetry"), or empty if unknown.
std::string_view packet_name(std::uint8_t id);
// Packet id from its name; false if unknown.
bool packet_id(std::string_view name, std::uint8_t& id);

}  // namespace gimbal::orion
