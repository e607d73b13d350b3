#include "protocols/mavlink_device/mavlink_device_options.hpp"

namespace gimbal::protocols {

namespace {

template <class T>
void read(const nlohmann::json& from, const char* key, T& to) {
    const auto it = from.find(key);
    if (it == from.end() || !it->is_number()) return;
    to = it->get<T>();
}

}  // namespace

MavlinkDeviceOptions read_mavlink_device_options(const nlohmann::json& gimbal) {
    MavlinkDeviceOptions o;
    const auto it = gimbal.find("mavlink");
    if (it == gimbal.end() || !it->is_object()) return o;
    const nlohmann::json& m = *it;
    read(m, "system_id", o.system_id);
    read(m, "component_id", o.component_id);
    read(m, "device_component_id", o.device_component_id);
    read(m, "hfov_deg", o.hfov_deg);
    read(m, "vfov_deg", o.vfov_deg);
    read(m, "geoid_undulation_m", o.geoid_undulation_m);
    read(m, "ground_alt_m", o.ground_alt_m);
    if (const auto key = m.find("signing_key_file"); key != m.end() && key->is_string())
        o.signing_key_file = key->get<std::string>();
    return o;
}

}  // namespace gimbal::protocols
