// A protocol's UDP broadcast discovery, as its vendor SDK does it: the datagram gimbald
// broadcasts to find a gimbal (a TCP link with host "discover") and how it knows an answer,
// whose source address is the gimbal's. Pure; daemon/link/discovery.cpp does the sockets.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace gimbal::protocols {

struct Discovery {
    std::vector<std::uint8_t> (*request)() = nullptr;  // null: the protocol has no discovery
    bool (*is_reply)(std::span<const std::uint8_t> datagram) = nullptr;

    explicit operator bool() const { return request != nullptr && is_reply != nullptr; }
};

}  // namespace gimbal::protocols
