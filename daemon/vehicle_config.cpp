#include "vehicle_config.hpp"

namespace gimbal::daemon {

void read_source(config::Fields& f, VehicleConfig& c) {
    f.section("source", [&c](config::Fields& source) {
        std::string type;
        if (!source.choice("type", type, {"udp", "serial"}, config::Presence::required)) {
            source.keep_unknown_keys();  // which keys belong here depends on the type
            return;
        }
        if (type == "udp") {
            UdpSource udp;
            fields(source, udp);
            c.source = udp;
        } else {
            SerialSource serial;
            fields(source, serial);
            c.source = serial;
        }
    });
}

nlohmann::json write_source(const VehicleConfig& c) {
    return std::visit(
        [](const auto& source) {
            nlohmann::json out = config::write(source);
            out["type"] =
                std::is_same_v<std::decay_t<decltype(source)>, UdpSource> ? "udp" : "serial";
            return out;
        },
        c.source);
}

}  // namespace gimbal::daemon
