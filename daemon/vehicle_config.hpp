// `vehicle` (contract section 3): where the autopilot's MAVLink comes from (UDP or serial),
// which system to follow and when it is stale. Declared once here and read and written by the
// generic reader (lib/config/fields.hpp); VehicleSource takes it.
#pragma once

#include <boost/asio/ip/address.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "address_field.hpp"
#include "config/fields.hpp"
#include "link/link_config.hpp"

namespace gimbal::daemon {

// MAVLink from the autopilot.
struct UdpSource {
    boost::asio::ip::address bind = boost::asio::ip::make_address_v4("127.0.0.1");
    std::uint16_t port = 14550;
    bool operator==(const UdpSource&) const = default;
};

struct SerialSource {
    std::string device;
    std::uint32_t baud = 0;
    bool operator==(const SerialSource&) const = default;
};

struct VehicleConfig {
    std::variant<UdpSource, SerialSource> source = UdpSource{};
    std::optional<std::uint8_t> system_id;  // empty: the first autopilot heard
    double timeout_s = 1.0;
    bool operator==(const VehicleConfig&) const = default;
};

template <class V>
void fields(V& v, UdpSource& c) {
    address(v, "bind", c.bind);
    v.integer("port", c.port, {1, 65535});
}

template <class V>
void fields(V& v, SerialSource& c) {
    serial_port_fields(v, c.device, c.baud);
}

// `source`: its `type` chooses the struct.
void read_source(config::Fields& f, VehicleConfig& c);
nlohmann::json write_source(const VehicleConfig& c);

template <class V>
void fields(V& v, VehicleConfig& c) {
    if constexpr (V::reading)
        read_source(v, c);
    else
        v.set_json("source", write_source(c));
    v.optional_integer("system_id", c.system_id, {1, 255});
    v.number("timeout_s", c.timeout_s, {0.1, 60});
}

}  // namespace gimbal::daemon
