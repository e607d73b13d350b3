// mqtt.url (contract section 9): "mqtt://host:port" or "mqtts://host:port" (TLS). Pure.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "result/result.hpp"

namespace gimbal::daemon {

struct MqttUrl {
    bool tls = false;
    std::string host;  // name, IPv4, or IPv6 without the brackets
    std::uint16_t port = 1883;
};

// The URL, or bad_request saying what is wrong with it. The port defaults to 1883 (mqtt) and
// 8883 (mqtts); IPv6 hosts are written in brackets ("mqtt://[::1]:1883"). No user
// information, path or query: credentials go in `username`/`password_file`.
Result<MqttUrl> parse_mqtt_url(std::string_view text);

}  // namespace gimbal::daemon
