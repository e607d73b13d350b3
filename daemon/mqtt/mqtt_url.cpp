#include "mqtt_url.hpp"

#include <algorithm>
#include <charconv>

namespace gimbal::daemon {

namespace {
Error bad(std::string message) {
    return {code::bad_request, std::move(message)};
}
}  // namespace

Result<MqttUrl> parse_mqtt_url(std::string_view text) {
    const std::string usage = "must be mqtt://HOST[:PORT] or mqtts://HOST[:PORT]";
    MqttUrl url;
    std::string_view rest;
    if (text.starts_with("mqtt://")) {
        rest = text.substr(7);
    } else if (text.starts_with("mqtts://")) {
        url.tls = true;
        url.port = 8883;
        rest = text.substr(8);
    } else {
        return bad(usage);
    }
    if (!rest.empty() && rest.back() == '/') rest.remove_suffix(1);
    if (rest.find_first_of("/?#@ \t") != std::string_view::npos)
        return bad(usage +
                   " (no user, path or query: credentials go in username and password_file)");
    std::string_view host = rest;
    std::string_view port;
    if (rest.starts_with("[")) {
        const auto close = rest.find(']');
        if (close == std::string_view::npos) return bad(usage + " (unclosed '[')");
        host = rest.substr(1, close - 1);
        const auto after = rest.substr(close + 1);
        if (!after.empty()) {
            if (after.front() != ':') return bad(usage);
            port = after.substr(1);
            if (port.empty()) return bad(usage + " (empty port)");
        }
    } else if (const auto colon = rest.rfind(':'); colon != std::string_view::npos) {
        host = rest.substr(0, colon);
        port = rest.substr(colon + 1);
        if (host.find(':') != std::string_view::npos)
            return bad(usage + " (write IPv6 hosts in brackets)");
        if (port.empty()) return bad(usage + " (empty port)");
    }
    if (host.empty() || host.size() > 253 ||
        std::any_of(host.begin(), host.end(), [](char c) { return c <= ' ' || c > '~'; }))
        return bad(usage + " (no host)");
    if (!port.empty()) {
        unsigned value = 0;
        const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
        if (ec != std::errc{} || end != port.data() + port.size() || value < 1 || value > 65535)
            return bad("port must be 1..65535");
        url.port = static_cast<std::uint16_t>(value);
    }
    url.host = std::string(host);
    return url;
}

}  // namespace gimbal::daemon
