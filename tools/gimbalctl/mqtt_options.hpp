// --mqtt URL --station NAME (and the broker's TLS/login options): send requests through an
// MQTT broker to a gimbald's `{prefix}/{station}/cmd` topic instead of its UDP socket
// (contract section 9), and `watch` its published STATE and events.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace gimbalctl {

struct MqttTarget {
    std::string url;      // mqtt://HOST[:PORT] or mqtts://HOST[:PORT]
    std::string station;  // a station name, or "+" (watch only) for all
    std::string prefix = "gimbald";
    std::optional<std::string> ca_file;  // mqtts: CA of the broker's certificate
    std::optional<std::string> username;
    std::optional<std::string> password_file;
};

struct MqttOptionsRaw {
    MqttTarget target;
    std::string ca_file;
    std::string username;
    std::string password_file;
    bool given = false;
};

// Adds --mqtt, --station, --mqtt-prefix, --mqtt-ca, --mqtt-user, --mqtt-password-file.
void add_mqtt_options(CLI::App& app, MqttOptionsRaw& raw);
// The target when --mqtt was given (then --station is required), else nullopt.
std::optional<MqttTarget> finish_mqtt_options(const CLI::App& app, const MqttOptionsRaw& raw);

}  // namespace gimbalctl
