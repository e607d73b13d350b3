#include "auth/signed_envelope.hpp"

#include "auth/hmac.hpp"

namespace gimbal::auth {

command::Result<std::optional<SignedEnvelope>> parse_signed(const nlohmann::json& datagram) {
    namespace code = command::code;
    if (!datagram.is_object()) return std::optional<SignedEnvelope>{};
    const auto it = datagram.find("signed");
    if (it == datagram.end()) return std::optional<SignedEnvelope>{};
    if (datagram.size() != 1)
        return {code::bad_request, "a signed datagram holds only the \"signed\" object"};
    const auto& s = *it;
    if (!s.is_object()) return {code::bad_request, "\"signed\" must be an object"};
    SignedEnvelope env;
    for (const auto& [name, value] : s.items()) {
        if (!value.is_string())
            return {code::bad_request, "\"signed\"." + name + " must be a string"};
        if (name == "key")
            env.key = value.get<std::string>();
        else if (name == "payload")
            env.payload = value.get<std::string>();
        else if (name == "mac")
            env.mac = value.get<std::string>();
        else
            return {code::bad_request, "\"signed\" has an unknown member '" + name + "'"};
    }
    if (!s.contains("key") || !s.contains("payload") || !s.contains("mac"))
        return {code::bad_request, "\"signed\" needs \"key\", \"payload\" and \"mac\""};
    return std::optional<SignedEnvelope>{std::move(env)};
}

bool mac_matches(const SignedEnvelope& envelope, std::span<const std::uint8_t> secret) {
    const auto received = from_hex(envelope.mac);
    if (!received) return false;
    const Mac expected = hmac_sha256(secret, envelope.payload);
    return equal_constant_time(*received, expected);
}

std::string sign(std::string_view key_id, std::span<const std::uint8_t> secret,
                 const std::string& payload) {
    const nlohmann::json datagram = {
        {"signed",
         {{"key", key_id}, {"payload", payload}, {"mac", to_hex(hmac_sha256(secret, payload))}}}};
    return datagram.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace gimbal::auth
