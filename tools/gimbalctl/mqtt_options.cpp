#include "mqtt_options.hpp"

#include <CLI/CLI.hpp>

namespace gimbalctl {

void add_mqtt_options(CLI::App& app, MqttOptionsRaw& raw) {
    app.add_option("--mqtt", raw.target.url,
                   "send through this MQTT broker instead of the UDP socket: mqtt://HOST[:PORT] "
                   "or mqtts://HOST[:PORT] (TLS); needs --station")
        ->type_name("URL")
        ->default_str("UDP");
    app.add_option("--station", raw.target.station,
                   "with --mqtt: the gimbald station to command (its mqtt.station); watch "
                   "also takes + for every station")
        ->type_name("NAME");
    app.add_option("--mqtt-prefix", raw.target.prefix, "with --mqtt: the topic prefix")
        ->type_name("PREFIX")
        ->default_str("gimbald");
    app.add_option("--mqtt-ca", raw.ca_file, "with mqtts://: CA file of the broker's certificate")
        ->type_name("FILE")
        ->default_str("/etc/ssl/certs");
    app.add_option("--mqtt-user", raw.username, "with --mqtt: broker login name")
        ->type_name("NAME");
    app.add_option("--mqtt-password-file", raw.password_file,
                   "with --mqtt: file holding the broker password (one line)")
        ->type_name("FILE");
}

std::optional<MqttTarget> finish_mqtt_options(const CLI::App& app, const MqttOptionsRaw& raw) {
    if (app.count("--mqtt") == 0) {
        if (app.count("--station") > 0) throw CLI::ValidationError("--station", "only with --mqtt");
        return std::nullopt;
    }
    if (app.count("--station") == 0 || raw.target.station.empty())
        throw CLI::RequiredError("--station (with --mqtt)");
    if (raw.target.url.rfind("mqtt://", 0) != 0 && raw.target.url.rfind("mqtts://", 0) != 0)
        throw CLI::ValidationError("--mqtt", "must be mqtt://HOST[:PORT] or mqtts://HOST[:PORT]");
    MqttTarget target = raw.target;
    if (app.count("--mqtt-ca") > 0) target.ca_file = raw.ca_file;
    if (app.count("--mqtt-user") > 0) target.username = raw.username;
    if (app.count("--mqtt-password-file") > 0) target.password_file = raw.password_file;
    return target;
}

}  // namespace gimbalctl
