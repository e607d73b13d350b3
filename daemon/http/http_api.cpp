#include "http_api.hpp"

#include <boost/beast/http/field.hpp>
#include <boost/beast/http/verb.hpp>
#include <cstdio>

#include "health.hpp"
#include "metrics_page.hpp"
#include "static_files.hpp"

namespace gimbald::http {

namespace beast = boost::beast;
using beast::http::field;
using beast::http::status;
using beast::http::verb;
using nlohmann::json;

namespace {

constexpr std::uintmax_t max_static_file = 16u * 1024 * 1024;

Response make(status code, unsigned version, std::string_view type, std::string body) {
    Response res{code, version};
    res.set(field::server, "gimbald/" GIMBALD_VERSION);
    res.set(field::content_type, std::string(type));
    res.body() = std::move(body);
    return res;
}

Response json_response(status code, unsigned version, const json& body) {
    auto res = make(code, version, "application/json",
                    body.dump(-1, ' ', false, json::error_handler_t::replace));
    res.set(field::cache_control, "no-store");
    return res;
}

bool read_only(verb method) {
    return method == verb::get || method == verb::head;
}

Response method_not_allowed(unsigned version, std::string_view allow) {
    auto res = HttpApi::error(status::method_not_allowed, version,
                              "method not allowed; allowed: " + std::string(allow));
    res.set(field::allow, std::string(allow));
    return res;
}

std::optional<std::string> read_file(const std::filesystem::path& path) {
    std::FILE* file = std::fopen(path.c_str(), "rbe");
    if (file == nullptr) return std::nullopt;
    std::string text;
    char buffer[16384];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, file)) > 0;)
        text.append(buffer, n);
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed) return std::nullopt;
    return text;
}

}  // namespace

HttpApi::HttpApi(DaemonView daemon, ApiOptions options, HttpStats& stats)
    : daemon_(std::move(daemon)), options_(std::move(options)), stats_(stats) {
    daemon_.path->add_observer([this](const CompletedRequest& done) { commands_.observe(done); });
}

Response HttpApi::error(status code, unsigned version, std::string text) {
    return json_response(code, version, {{"error", std::move(text)}});
}

std::optional<std::string> video_gimbal(std::string_view path) {
    constexpr std::string_view prefix = "/api/video/";
    if (!path.starts_with(prefix)) return std::nullopt;
    auto name = percent_decode(path.substr(prefix.size()));
    if (!name || name->empty() || name->find('/') != std::string::npos) return std::nullopt;
    return name;
}

std::optional<std::string> HttpApi::cross_site_problem(const Request& request) const {
    const auto text = [&](field f) {
        const auto value = request[f];
        return std::string_view(value.data(), value.size());
    };
    const auto host = text(field::host);
    auto problem = host_problem(host, options_.site);
    const std::string path(target_path(std::string(request.target())));
    // The video WebSocket too: a page of another site must not watch the gimbal's video.
    const bool acts =
        path == "/api/command" || path == "/api/stream" || video_gimbal(path).has_value();
    if (!problem && acts) problem = origin_problem(text(field::origin), host);
    return problem;
}

Response HttpApi::handle(const Request& request, const std::string& source) {
    const std::string target(request.target());
    const std::string path(target_path(target));
    const unsigned version = request.version();
    const verb method = request.method();

    if (path == "/api/command") {
        if (method != verb::post) return method_not_allowed(version, "POST");
        return command(request, source);
    }
    if (path == "/metrics" || path == "/healthz" || path == "/api/state" ||
        path == "/api/console" || path == "/api/stream") {
        if (!read_only(method)) return method_not_allowed(version, "GET, HEAD");
    }
    if (path == "/metrics") {
        auto res = make(status::ok, version, metrics_content_type,
                        render_metrics(daemon_, commands_, stats_));
        res.set(field::cache_control, "no-store");
        return res;
    }
    if (path == "/healthz") {
        const auto health = check_health(daemon_.path->sessions());
        return json_response(health.ok ? status::ok : status::service_unavailable, version,
                             health.body);
    }
    if (path == "/api/state") {
        json gimbals = json::object();
        for (auto* session : daemon_.path->sessions())
            gimbals[session->name()] = session->snapshot();
        return json_response(status::ok, version, {{"gimbals", std::move(gimbals)}});
    }
    if (path == "/api/console") return json_response(status::ok, version, console_info());
    if (const auto gimbal = video_gimbal(path)) {
        if (!read_only(method)) return method_not_allowed(version, "GET, HEAD");
        if (!daemon_.video || !daemon_.video(*gimbal))
            return error(status::not_found, version,
                         "no gimbal '" + *gimbal + "' with a video section");
        return error(
            status::upgrade_required, version,
            "/api/video/" + *gimbal + " is a WebSocket: send a GET with Upgrade: websocket");
    }
    if (path == "/api/stream")
        return error(status::upgrade_required, version,
                     "/api/stream is a WebSocket: send a GET with Upgrade: websocket");
    if (options_.console) return static_file(request);
    return error(status::not_found, version, "no such path");
}

Response HttpApi::command(const Request& request, const std::string& source) {
    const RequestSource from{"http", source, std::nullopt};
    auto reply = daemon_.path->handle(request.body(), from);
    // Over command.rate_limit, past the one refusal reply a second: nothing was executed.
    if (!reply)
        return error(status::too_many_requests, request.version(),
                     "rate limited (command.rate_limit)");
    auto res = make(status::ok, request.version(), "application/json", std::move(*reply));
    res.set(field::cache_control, "no-store");
    return res;
}

Response HttpApi::too_large(unsigned version, const std::string& source,
                            std::optional<std::size_t> size) {
    const RequestSource from{"http", source, std::nullopt};
    auto reply = daemon_.path->refuse_too_large(size, from);
    if (!reply)
        return error(status::too_many_requests, version, "rate limited (command.rate_limit)");
    auto res = make(status::payload_too_large, version, "application/json", std::move(*reply));
    res.set(field::cache_control, "no-store");
    return res;
}

Response HttpApi::static_file(const Request& request) {
    const auto file = resolve_static(options_.web_root, std::string(request.target()));
    if (!file) return error(status::not_found, request.version(), "no such path");
    if (!read_only(request.method())) return method_not_allowed(request.version(), "GET, HEAD");
    std::error_code ec;
    const auto size = std::filesystem::file_size(*file, ec);
    if (ec || size > max_static_file)
        return error(status::internal_server_error, request.version(), "cannot serve that file");
    auto body = read_file(*file);
    if (!body)
        return error(status::internal_server_error, request.version(), "cannot read that file");
    auto res = make(status::ok, request.version(), content_type(*file), std::move(*body));
    // The console changes with the daemon: a browser revalidates rather than keep an old one.
    res.set(field::cache_control, "no-cache");
    res.set("X-Content-Type-Options", "nosniff");
    return res;
}

json HttpApi::console_info() const {
    json gimbals = json::array();
    for (auto* session : daemon_.path->sessions())
        gimbals.push_back({{"name", session->name()},
                           {"protocol", std::string(session->protocol())},
                           // Contract section 18: GET /api/video/{name} serves its video.
                           {"video", daemon_.video && daemon_.video(session->name()) != nullptr},
                           // Contract section 20: its video has `tracking` (a box starts one).
                           {"tracking", static_cast<bool>(session->view().track)}});
    const auto& config = *daemon_.config;
    return {{"version", GIMBALD_VERSION},
            {"gimbals", std::move(gimbals)},
            {"laser_allow_fire", config.laser.allow_fire},
            // Contract section 15: with terrain, a click's geopoint leaves `alt` to it.
            {"terrain", config.terrain.has_value()},
            {"tiles_url", config.http && config.http->tiles_url ? json(*config.http->tiles_url)
                                                                : json(nullptr)}};
}

}  // namespace gimbald::http
