// A MAVLink gimbal device's own configuration keys (contract section 19): `mavlink`, gimbald's
// ids on the device link, the device's component, what the device does not report (fields of
// view, the geoid and flat-ground heights) and the signing key. Declared once here;
// daemon/config.cpp reads and writes it through the registry (mavlink_device_entry.cpp), and
// MavlinkDeviceOptions is this struct plus what the daemon adds at run time.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "command/result.hpp"
#include "config/fields.hpp"
#include "mavlink/signing.hpp"

namespace gimbal::protocols {

struct MavlinkDeviceConfig {
    // Who gimbald is on the device link (the gimbal manager, usually the autopilot's ids).
    std::uint8_t system_id = 1;
    std::uint8_t component_id = 1;
    // The device's component (MAV_COMP_ID_GIMBAL unless it says otherwise).
    std::uint8_t device_component_id = 154;
    // The camera's fields of view when the device reports none (degrees).
    double hfov_deg = 60;
    double vfov_deg = 34;
    // The geoid's height above the ellipsoid where the aircraft flies (metres): the vehicle
    // reports MSL altitudes, STATE and geometry use the ellipsoid. A number is a fixed
    // override; null (the default): the EGM96 geoid at the aircraft's position
    // (MavlinkDeviceOptions::geoid), else 0.
    std::optional<double> geoid_undulation_m;
    // The flat world where no terrain answers: this altitude above the ellipsoid (metres).
    double ground_alt_m = 0;
    // MAVLink 2 message signing on the device link (docs/mavlink-device.md).
    std::optional<std::string> signing_key_file;
    bool operator==(const MavlinkDeviceConfig&) const = default;
};

template <class V>
void fields(V& v, MavlinkDeviceConfig& c) {
    v.section("mavlink", [&](auto& m) {
        m.integer("system_id", c.system_id, {1, 255});
        m.integer("component_id", c.component_id, {1, 255});
        m.integer("device_component_id", c.device_component_id, {1, 255});
        m.number("hfov_deg", c.hfov_deg, {0.1, 179.9});
        m.number("vfov_deg", c.vfov_deg, {0.1, 179.9});
        m.optional_number("geoid_undulation_m", c.geoid_undulation_m, {-200, 200});
        m.number("ground_alt_m", c.ground_alt_m, {-2000, 10000});
        m.optional_string("signing_key_file", c.signing_key_file);
    });
}

// The key in `path`, read by `read_secret` (owner-only, as every secret file), or an error
// naming the file: at --check-config and start (config.cpp) and when the session opens.
using SecretReader = std::function<command::Result<std::string>(const std::string& path)>;
command::Result<mavlink::SigningKey> load_signing_key(const std::string& path,
                                                      const SecretReader& read_secret);

}  // namespace gimbal::protocols
