#include "mqtt/mqtt_config.hpp"

#include <unistd.h>

#include <fmt/format.h>
#include <cctype>
#include <regex>
#include <variant>

#include "mqtt/mqtt_url.hpp"
#include "protocols/registry.hpp"
#include "regular_file.hpp"
#include "secret_file.hpp"
#include "state/messages.hpp"

namespace gimbal::daemon {

namespace {

const std::regex station_pattern("[a-z0-9_-]{1,32}");

// The host name lower-cased, every character outside [a-z0-9_-] replaced by '-', cut at 32.
std::string default_station() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "gimbald";
    std::string station;
    for (const char* c = name; *c != '\0' && station.size() < 32; ++c) {
        const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(*c)));
        const bool ok = (lower >= 'a' && lower <= 'z') || (lower >= '0' && lower <= '9') ||
                        lower == '_' || lower == '-';
        station += ok ? lower : '-';
    }
    return station;
}

// A file named in the config that must be readable now (CA, certificate).
void check_readable(config::Fields& f, std::string_view key,
                    const std::optional<std::string>& path) {
    if (!path) return;
    // Opened without blocking and regular only: a FIFO here would hang --check-config.
    if (const auto problem = check_regular_file(*path)) f.problem(key, problem->message);
}

}  // namespace

void read_url(config::Fields& f, MqttConfig& c) {
    if (!f.string("url", c.url)) return;
    const auto url = parse_mqtt_url(c.url);
    if (url) {
        c.tls = url->tls;
        c.host = url->host;
        c.port = url->port;
    } else {
        f.problem("url", url.error().message);
    }
}

void read_station(config::Fields& f, MqttConfig& c) {
    std::optional<std::string> station;
    f.optional_string("station", station);
    if (station && !std::regex_match(*station, station_pattern))
        f.problem("station", "must match [a-z0-9_-]{1,32}");
    c.station = station ? *station : default_station();
}

bool valid_prefix(const std::string& p) {
    return !(p.empty() || p.size() > 128 || p.front() == '/' || p.back() == '/' ||
             p.find("//") != std::string::npos || p.find_first_of("+#") != std::string::npos);
}

void read_client_id(config::Fields& f, MqttConfig& c) {
    std::optional<std::string> client_id;
    f.optional_string("client_id", client_id);
    if (client_id && client_id->size() > 128) f.problem("client_id", "longer than 128 characters");
    c.client_id = client_id ? *client_id : "gimbald-" + c.station;
}

void read_password(config::Fields& f, MqttConfig& c) {
    if (!c.password_file) return;
    const auto text = read_secret_file(*c.password_file);
    if (!text) {
        f.problem("password_file", text.error().message);
    } else {
        c.password = *text;
        // One line: the trailing newline an editor adds is not part of the password.
        while (!c.password.empty() && (c.password.back() == '\n' || c.password.back() == '\r'))
            c.password.pop_back();
    }
    if (!c.username) f.problem("password_file", "needs \"username\"");
}

void check_tls_files(config::Fields& f, const MqttConfig& c) {
    check_readable(f, "ca_file", c.ca_file);
    check_readable(f, "cert_file", c.cert_file);
    if (c.key_file) {
        const auto key = read_secret_file(*c.key_file);
        if (!key) f.problem("key_file", key.error().message);
    }
    if (c.cert_file.has_value() != c.key_file.has_value())
        f.problem(c.cert_file ? "key_file" : "cert_file",
                  "cert_file and key_file go together (the client certificate and its key)");
    if (!c.tls && (c.ca_file || c.cert_file))
        f.problem("url", "ca_file/cert_file are set: use mqtts:// for TLS");
}

void read_state_keys(config::Fields& f, MqttConfig& c) {
    const auto* keys = f.find("state_keys");
    if (keys == nullptr || keys->is_null()) return;
    auto names = gimbal::state::read_state_keys(*keys, gimbal::protocols::is_state_key);
    if (!names)
        f.problem("state_keys", names.error().message);
    else
        c.state_keys = std::move(names).value();
}

}  // namespace gimbal::daemon
