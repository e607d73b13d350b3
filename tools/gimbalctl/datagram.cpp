#include "datagram.hpp"

namespace gimbalctl {

std::optional<Json> parse_datagram(std::string_view datagram) {
    Json value = Json::parse(datagram.begin(), datagram.end(), nullptr, false);
    if (value.is_discarded() || !value.is_object()) return std::nullopt;
    return value;
}

namespace {

// The daemon refuses a request over its size or nesting limits without reading it, so the
// refusal cannot carry the request's id (contract section 14): "id" is null or absent.
bool refused_unread(const Json& datagram) {
    const auto ok = datagram.find("ok");
    const auto id = datagram.find("id");
    const auto error = datagram.find("error");
    if (ok == datagram.end() || *ok != false || (id != datagram.end() && !id->is_null()) ||
        error == datagram.end() || !error->is_object())
        return false;
    const auto code = error->find("code");
    return code != error->end() && (*code == "too_large" || *code == "bad_json");
}

}  // namespace

bool is_reply_to(const Json& datagram, const Json& request) {
    const auto id = datagram.find("id");
    const auto request_id = request.find("id");
    if (request_id == request.end() || !datagram.contains("ok")) return false;
    // On gimbalctl's own socket, an unread refusal answers the one request in flight.
    return (id != datagram.end() && *id == *request_id) || refused_unread(datagram);
}

bool is_subscription_datagram(const Json& datagram) {
    return datagram.contains("type") && !datagram.contains("ok");
}

}  // namespace gimbalctl
