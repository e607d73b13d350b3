#include "protocols/mavlink_device/mavlink_device_options.hpp"

namespace gimbal::protocols {

MavlinkDeviceOptions read_mavlink_device_options(const nlohmann::json& gimbal) {
    MavlinkDeviceOptions o;
    static_cast<MavlinkDeviceConfig&>(o) = config::read_checked<MavlinkDeviceConfig>(gimbal);
    return o;
}

command::Result<mavlink::SigningKey> load_signing_key(const std::string& path,
                                                      const SecretReader& read_secret) {
    if (!read_secret)
        return command::Error{command::code::internal, path + ": no way to read a key file here"};
    const auto text = read_secret(path);
    if (!text) return text.error();
    if (auto key = mavlink::parse_signing_key(*text)) return *key;
    return command::Error{command::code::bad_request,
                          path + ": must hold 32 bytes, or 64 hex digits"};
}

}  // namespace gimbal::protocols
