#include "auth/signed_envelope.hpp"

#include "auth/hmac.hpp"

namespace gimbal::auth {

std::optional<std::variant<SignedEnvelope, std::string>> read_signed(
    const nlohmann::json& datagram) {
    if (!datagram.is_object()) return std::nullopt;
    const auto it = datagram.find("signed");
    if (it == datagram.end()) return std::nullopt;
    using Result = std::variant<SignedEnvelope, std::string>;
    if (datagram.size() != 1)
        return Result{std::string("a signed datagram holds only the \"signed\" object")};
    const auto& s = *it;
    if (!s.is_object()) return Result{std::string("\"signed\" must be an object")};
    SignedEnvelope env;
    for (const auto& [name, value] : s.items()) {
        if (!value.is_string()) return Result{"\"signed\"." + name + " must be a string"};
        if (name == "key")
            env.key = value.get<std::string>();
        else if (name == "payload")
            env.payload = value.get<std::string>();
        else if (name == "mac")
            env.mac = value.get<std::string>();
        else
            return Result{"\"signed\" has an unknown member '" + name + "'"};
    }
    if (!s.contains("key") || !s.contains("payload") || !s.contains("mac"))
        return Result{std::string("\"signed\" needs \"key\", \"payload\" and \"mac\"")};
    return Result{std::move(env)};
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
