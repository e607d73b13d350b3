#include "health.hpp"

namespace gimbald::http {

using nlohmann::json;

Health check_health(const std::vector<GimbalSession*>& sessions) {
    Health health;
    json gimbals = json::object();
    json problems = json::array();
    for (const auto* session : sessions) {
        const bool connected = session->connected();
        const bool stale = session->stale();
        if (!connected) problems.push_back(session->name() + ": link down");
        if (stale) problems.push_back(session->name() + ": telemetry stale");
        gimbals[session->name()] = {
            {"connected", connected}, {"stale", stale}, {"ok", connected && !stale}};
    }
    health.ok = problems.empty();
    health.body = {{"ok", health.ok},
                   {"version", GIMBALD_VERSION},
                   {"gimbals", std::move(gimbals)},
                   {"problems", std::move(problems)}};
    return health;
}

}  // namespace gimbald::http
