// A gimbal's `link` (contract sections 3 and 19): TCP, serial, UDP or the embedded simulator.
// Declared once here and read and written by the generic reader (lib/config/fields.hpp); the
// links' option structs (tcp_link.hpp, serial_link.hpp, udp_link.hpp) derive from these.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "config/fields.hpp"

namespace gimbal::daemon {

// The termios rates from 1200 baud up; a serial link's `baud` must be one of them.
std::span<const std::uint32_t> standard_baud_rates();

struct TcpLink {
    std::string host;  // name or address, or "discover" (Orion SDK broadcast discovery)
    std::uint16_t port = 0;
    double connect_timeout_s = 3.0;
    double reconnect_min_s = 0.2;
    double reconnect_max_s = 5.0;
    double silence_timeout_s = 3.0;  // no byte for this long: the peer is dead, reconnect
    // Used only when host is "discover".
    std::string discover_address = "255.255.255.255";
    std::uint16_t discover_port = 8745;
    std::uint16_t discover_reply_port = 8746;

    bool discover() const { return host == "discover"; }
    bool operator==(const TcpLink&) const = default;
};

struct SerialLink {
    std::string device;
    std::uint32_t baud = 0;  // 8N1, no flow control
    double reconnect_min_s = 0.2;
    double reconnect_max_s = 5.0;
    bool operator==(const SerialLink&) const = default;
};

struct SimLink {
    bool operator==(const SimLink&) const = default;
};

// Datagrams to host:port from local_port (an ephemeral port when unset); only host's are
// taken (contract section 19, MAVLink gimbal devices).
struct UdpLink {
    std::string host;
    std::uint16_t port = 0;
    std::optional<std::uint16_t> local_port;
    double reconnect_min_s = 0.2;
    double reconnect_max_s = 5.0;
    bool operator==(const UdpLink&) const = default;
};

using Link = std::variant<TcpLink, SerialLink, SimLink, UdpLink>;
std::string_view link_type(const Link& link);  // "tcp", "serial", "sim", "udp"
// "192.168.1.20:8747", "[fe80::1]:8747", "discover via 255.255.255.255:8745",
// "/dev/ttyUSB0@115200", "sim"
std::string describe(const Link& link);

// The `link` object: its `type` chooses the struct. nullopt when the type is missing or
// unknown (reported; the object's other keys are then not checked).
std::optional<Link> read_link(config::Fields& f);
nlohmann::json write_link(const Link& link);

// Keys several sections share (the vehicle's serial source too).
void read_baud(config::Fields& f, std::string_view key, std::uint32_t& out);  // required
void read_device(config::Fields& f, std::string_view key, std::string& out);  // required
bool valid_host(const std::string& host);  // a name or address: printable, 1..253
void check_reconnect(config::Fields& f, double min_s, double max_s);
void read_discover_address(config::Fields& f, std::string& out);  // IPv4

template <class V>
void reconnect_fields(V& v, double& min_s, double& max_s) {
    v.number("reconnect_min_s", min_s, {0.01, 60});
    v.number("reconnect_max_s", max_s, {0.1, 3600});
    if constexpr (V::reading) check_reconnect(v, min_s, max_s);
}

template <class V>
void fields(V& v, TcpLink& c) {
    if (v.string("host", c.host, config::Presence::required) && !valid_host(c.host))
        v.problem("host", "must be a host name, an IP address or \"discover\"");
    v.integer("port", c.port, {1, 65535}, config::Presence::required);
    v.number("connect_timeout_s", c.connect_timeout_s, {0.1, 60});
    reconnect_fields(v, c.reconnect_min_s, c.reconnect_max_s);
    v.number("silence_timeout_s", c.silence_timeout_s, {0.1, 3600});
    if constexpr (V::reading)
        read_discover_address(v, c.discover_address);
    else
        v.string("discover_address", c.discover_address);
    v.integer("discover_port", c.discover_port, {1, 65535});
    v.integer("discover_reply_port", c.discover_reply_port, {1, 65535});
}

// A serial port's `device` and `baud`: a gimbal's serial link, the vehicle's serial source.
template <class V>
void serial_port_fields(V& v, std::string& device, std::uint32_t& baud) {
    if constexpr (V::reading) {
        read_device(v, "device", device);
        read_baud(v, "baud", baud);
    } else {
        v.string("device", device);
        v.integer("baud", baud, {});
    }
}

template <class V>
void fields(V& v, SerialLink& c) {
    serial_port_fields(v, c.device, c.baud);
    reconnect_fields(v, c.reconnect_min_s, c.reconnect_max_s);
}

template <class V>
void fields(V& v, UdpLink& c) {
    if (v.string("host", c.host, config::Presence::required) && !valid_host(c.host))
        v.problem("host", "must be a host name or an IP address");
    v.integer("port", c.port, {1, 65535}, config::Presence::required);
    v.optional_integer("local_port", c.local_port, {1, 65535});
    reconnect_fields(v, c.reconnect_min_s, c.reconnect_max_s);
}

template <class V>
void fields(V&, SimLink&) {}

}  // namespace gimbal::daemon
