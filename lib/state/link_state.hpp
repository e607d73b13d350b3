// STATE `link` (contract section 5): the gimbal link as the daemon sees it - its counters and
// the framer's. Filled by the gimbal's session at each snapshot.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace gimbal::state {

struct LinkState {
    std::string type;      // "serial", "tcp", "udp", "sim"
    std::string endpoint;  // the device, or host:port
    bool connected = false;
    std::uint64_t rx_bytes = 0;
    std::uint64_t tx_bytes = 0;
    std::uint64_t rx_packets = 0;  // valid frames from the gimbal
    std::uint64_t tx_packets = 0;
    std::uint64_t bad_checksums = 0;
    std::uint64_t dropped_bytes = 0;
    std::uint64_t reconnects = 0;
    std::optional<double> last_rx_age_s;  // nullopt: nothing received yet
};

template <class V>
void fields(V& v, const LinkState& l) {
    v.string("type", l.type);
    v.string("endpoint", l.endpoint);
    v.boolean("connected", l.connected);
    v.integer("rx_bytes", l.rx_bytes);
    v.integer("tx_bytes", l.tx_bytes);
    v.integer("rx_packets", l.rx_packets);
    v.integer("tx_packets", l.tx_packets);
    v.integer("bad_checksums", l.bad_checksums);
    v.integer("dropped_bytes", l.dropped_bytes);
    v.integer("reconnects", l.reconnects);
    v.seconds("last_rx_age_s", l.last_rx_age_s);
}

}  // namespace gimbal::state
