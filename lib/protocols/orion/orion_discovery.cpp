// The Orion SDK's gimbal discovery: a zero-length CROWN_VERSION request broadcast by UDP;
// any Orion frame that comes back answers it, from the gimbal's address.
#include "protocols/orion/orion_entry.hpp"

#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/framing.hpp"

namespace gimbal::protocols {

namespace {

std::vector<std::uint8_t> request() {
    return orion::request_bytes(orion::pkt::crown_version);
}

// Anything that is not an Orion frame (a stray datagram) is no answer.
bool is_reply(std::span<const std::uint8_t> datagram) {
    return datagram.size() >= 2 && datagram[0] == orion::sync0 && datagram[1] == orion::sync1;
}

}  // namespace

Discovery orion_discovery() {
    return {request, is_reply};
}

}  // namespace gimbal::protocols
