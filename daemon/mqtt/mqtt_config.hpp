// `mqtt` (contract section 9, docs/mqtt.md): the bridge to an MQTT broker; off unless the
// section is set. Declared once here and read and written by the generic reader
// (lib/config/fields.hpp); the bridge takes this struct.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/fields.hpp"

namespace gimbal::daemon {

struct MqttConfig {
    std::string url = "mqtt://127.0.0.1:1883";
    bool tls = false;  // mqtts://
    std::string host = "127.0.0.1";
    std::uint16_t port = 1883;
    std::string station;  // default: the host name, lower-cased, [^a-z0-9_-] -> '-'
    std::string prefix = "gimbald";
    std::string client_id;  // default: gimbald-{station}
    std::optional<std::string> username;
    std::optional<std::string> password_file;
    std::string password;  // read from password_file at load time, never printed
    std::optional<std::string> ca_file;
    std::optional<std::string> cert_file;
    std::optional<std::string> key_file;
    double keepalive_s = 10;
    double state_rate_hz = 2;
    std::optional<std::vector<std::string>> state_keys;
    bool state_changes = false;      // delta stream: merge patches between full STATEs
    double state_full_every_s = 10;  // with state_changes: a full STATE this often
    bool commands = false;
    unsigned queue_max = 1000;
    bool operator==(const MqttConfig&) const = default;
};

// Reading's own steps: the URL's parts, the names that default to the host's, the password
// read from its file, the TLS files, the STATE key list.
void read_url(config::Fields& f, MqttConfig& c);
void read_station(config::Fields& f, MqttConfig& c);
void read_client_id(config::Fields& f, MqttConfig& c);
void read_password(config::Fields& f, MqttConfig& c);
void check_tls_files(config::Fields& f, const MqttConfig& c);
void read_state_keys(config::Fields& f, MqttConfig& c);
bool valid_prefix(const std::string& prefix);

template <class V>
void fields(V& v, MqttConfig& c) {
    if constexpr (V::reading) {
        read_url(v, c);
        read_station(v, c);
    } else {
        v.string("url", c.url);
        v.string("station", c.station);
    }
    if (v.string("prefix", c.prefix) && !valid_prefix(c.prefix))
        v.problem("prefix",
                  "must be 1 to 128 characters of topic levels (no '+', '#', empty level or "
                  "leading/trailing '/')");
    if constexpr (V::reading)
        read_client_id(v, c);
    else
        v.string("client_id", c.client_id);
    v.optional_string("username", c.username);
    v.optional_string("password_file", c.password_file);
    if constexpr (V::reading) read_password(v, c);
    v.optional_string("ca_file", c.ca_file);
    v.optional_string("cert_file", c.cert_file);
    v.optional_string("key_file", c.key_file);
    if constexpr (V::reading) check_tls_files(v, c);
    v.number("keepalive_s", c.keepalive_s, {5, 3600});  // libmosquitto's minimum
    v.number("state_rate_hz", c.state_rate_hz, {0.1, 50});
    if constexpr (V::reading)
        read_state_keys(v, c);
    else
        v.set_json("state_keys", c.state_keys ? nlohmann::json(*c.state_keys) : nullptr);
    v.boolean("state_changes", c.state_changes);
    v.number("state_full_every_s", c.state_full_every_s, {1, 3600});
    v.boolean("commands", c.commands);
    v.integer("queue_max", c.queue_max, {10, 1000000});
}

}  // namespace gimbal::daemon
