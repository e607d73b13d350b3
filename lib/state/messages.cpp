#include "state/messages.hpp"

#include <algorithm>
#include <functional>
#include <iterator>
#include <utility>

namespace gimbal::state {

namespace {

// The top-level STATE keys every gimbal may have, whatever its protocol: the session's
// (contract section 5: protocol, link, stale), the shared typed part every protocol fills
// (telemetry, lasers, stare), and the daemon's own (vehicle, command, mavlink, mqtt, record,
// capabilities, video, track). A protocol's own keys (Orion's ins, Viewpro's output, ...) are its
// registry entry's (protocols::Entry::state_keys).
constexpr std::string_view shared_keys[] = {
    "protocol", "link",    "stale", "telemetry", "lasers",       "stare", "vehicle",
    "command",  "mavlink", "mqtt",  "record",    "capabilities", "video", "track"};

bool always_kept(std::string_view key) {
    return key == "protocol" || key == "link" || key == "stale";
}

}  // namespace

nlohmann::json state_message(const std::string& gimbal, nlohmann::json state) {
    return {{"type", "state"}, {"gimbal", gimbal}, {"state", std::move(state)}};
}

nlohmann::json event_message(const std::string& gimbal, const Event& event) {
    nlohmann::json msg = {{"type", "event"}, {"gimbal", gimbal}, {"event", event.kind}};
    for (const auto& [k, v] : event.fields.items()) msg[k] = v;
    return msg;
}

nlohmann::json too_large_event(const std::string& gimbal, std::size_t bytes, std::size_t limit,
                               const nlohmann::json& body) {
    std::vector<std::pair<std::size_t, std::string>> sizes;
    if (body.is_object())
        for (const auto& [k, v] : body.items())
            sizes.emplace_back(
                v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).size(), k);
    std::sort(sizes.begin(), sizes.end(), std::greater<>());
    if (sizes.size() > 3) sizes.resize(3);
    nlohmann::json largest = nlohmann::json::object();
    for (const auto& [n, k] : sizes) largest[k] = n;
    return {{"type", "event"},
            {"gimbal", gimbal},
            {"event", "too_large"},
            {"bytes", bytes},
            {"limit", limit},
            {"largest", std::move(largest)},
            {"message", "a push of " + std::to_string(bytes) +
                            " bytes is over the limit of one datagram (" + std::to_string(limit) +
                            " bytes) and was not sent; subscribe with fewer STATE keys ('keys')"}};
}

bool is_shared_state_key(std::string_view key) {
    return std::find(std::begin(shared_keys), std::end(shared_keys), key) != std::end(shared_keys);
}

nlohmann::json select_keys(const nlohmann::json& state, const std::vector<std::string>& keys) {
    if (keys.empty() || !state.is_object()) return state;
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [k, v] : state.items())
        if (always_kept(k) || std::find(keys.begin(), keys.end(), k) != keys.end()) out[k] = v;
    return out;
}

command::Result<std::vector<std::string>> read_state_keys(
    const nlohmann::json& value, const std::function<bool(std::string_view)>& is_known) {
    namespace code = command::code;
    if (!value.is_array()) return {code::bad_request, "'keys' must be an array of STATE key names"};
    std::vector<std::string> names;
    for (const auto& k : value) {
        if (!k.is_string())
            return {code::bad_request, "'keys' must be an array of STATE key names"};
        const auto& name = k.get_ref<const std::string&>();
        if (!is_known(name)) return {code::bad_request, "'keys': unknown STATE key '" + name + "'"};
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
    return names;
}

}  // namespace gimbal::state
