#include "auth/secret.hpp"

#include "auth/hmac.hpp"

namespace gimbal::auth {

std::variant<std::vector<std::uint8_t>, std::string> parse_secret(std::string_view text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) return std::string("the file is empty");
    const auto last = text.find_last_not_of(" \t\r\n");
    const std::string_view hex = text.substr(first, last - first + 1);
    if (hex.size() < 2 * min_secret_bytes)
        return "too short: " + std::to_string(hex.size()) + " hex characters, at least " +
               std::to_string(2 * min_secret_bytes) + " (32 bytes) are needed";
    auto bytes = from_hex(hex);
    if (!bytes) return std::string("not hex text (0-9, a-f, an even number of them)");
    return std::move(*bytes);
}

std::string new_secret_text() {
    return to_hex(random_bytes(min_secret_bytes)) + "\n";
}

}  // namespace gimbal::auth
