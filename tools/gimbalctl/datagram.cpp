#include "datagram.hpp"

namespace gimbalctl {

std::optional<Json> parse_datagram(std::string_view datagram) {
    Json value = Json::parse(datagram.begin(), datagram.end(), nullptr, false);
    if (value.is_discarded() || !value.is_object()) return std::nullopt;
    return value;
}

bool is_reply_to(const Json& datagram, const Json& request) {
    const auto id = datagram.find("id");
    const auto request_id = request.find("id");
    return id != datagram.end() && request_id != request.end() && *id == *request_id &&
           datagram.contains("ok");
}

bool is_subscription_datagram(const Json& datagram) {
    return datagram.contains("type") && !datagram.contains("ok");
}

}  // namespace gimbalctl
