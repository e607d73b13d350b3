// The HTTP paths of contract section 11 except the WebSocket upgrade: one request in, one
// response out. No socket here: HttpConnection reads and writes, this decides.
#pragma once

#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "command_metrics.hpp"
#include "daemon_view.hpp"
#include "site_check.hpp"

namespace gimbald::http {

using Request = boost::beast::http::request<boost::beast::http::string_body>;
using Response = boost::beast::http::response<boost::beast::http::string_body>;

struct ApiOptions {
    bool console = true;
    std::filesystem::path web_root;
    std::optional<std::string> tiles_url;
    SiteRules site;  // Host and Origin checks (site_check.hpp)
};

// The gimbal named by a /api/video/{gimbal} path (percent-decoded), else nullopt.
std::optional<std::string> video_gimbal(std::string_view path);

class HttpApi {
  public:
    HttpApi(DaemonView daemon, ApiOptions options, HttpStats& stats);

    // Why a browser was made to send this request from another site (wrong Host, or an
    // Origin that is not this server on a request that acts), else nullopt: answered 403
    // before anything else is looked at, the WebSocket upgrade included.
    std::optional<std::string> cross_site_problem(const Request& request) const;

    // `source`: "http:IP:PORT", the request path's `src`.
    Response handle(const Request& request, const std::string& source);

    // POST /api/command with a body over the request limit (`size` when declared): the
    // request path's too_large reply, unread, as a 413 (429 when rate-limited).
    Response too_large(unsigned version, const std::string& source,
                       std::optional<std::size_t> size);

    // A response for an HTTP-level problem (bad request, too large...): a JSON error body.
    static Response error(boost::beast::http::status status, unsigned version, std::string text);

    const std::filesystem::path& web_root() const { return options_.web_root; }

  private:
    Response command(const Request& request, const std::string& source);
    Response static_file(const Request& request);
    nlohmann::json console_info() const;

    DaemonView daemon_;
    ApiOptions options_;
    HttpStats& stats_;
    CommandMetrics commands_;
};

}  // namespace gimbald::http
