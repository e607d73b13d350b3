// `http` (contract section 11, docs/http.md): metrics, health, API, WebSocket stream and the
// operator console; off unless the section is set. Declared once here and read and written by
// the generic reader (lib/config/fields.hpp); HttpServerOptions derives from it.
#pragma once

#include <boost/asio/ip/address.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "address_field.hpp"
#include "config/fields.hpp"

namespace gimbal::daemon {

struct HttpConfig {
    boost::asio::ip::address bind = boost::asio::ip::make_address_v4("127.0.0.1");
    std::uint16_t port = 8761;
    bool console = true;                       // serve the console (GET / and static files)
    std::optional<std::string> tiles_url;      // XYZ template for the console's background map
    std::optional<std::string> web_root;       // null: the installed console directory
    unsigned max_connections = 64;             // HTTP and WebSocket connections together
    unsigned max_connections_per_client = 16;  // the same, from one client address
    double idle_timeout_s = 30;  // a request must arrive (its header then within 10 s)
    unsigned ws_queue_max = 64;  // messages queued for one WebSocket client
    // Host names browsers may use besides addresses and localhost (DNS-rebinding guard).
    std::vector<std::string> allowed_hosts;
    bool operator==(const HttpConfig&) const = default;
};

bool is_xyz_template(const std::string& url);     // has {z}, {x} and {y}
bool is_bare_host_name(const std::string& name);  // no port, path or brackets

template <class V>
void fields(V& v, HttpConfig& c) {
    address(v, "bind", c.bind);
    v.integer("port", c.port, {0, 65535});  // 0: any free port (tests)
    v.boolean("console", c.console);
    if (v.optional_string("tiles_url", c.tiles_url) && !is_xyz_template(*c.tiles_url))
        v.problem("tiles_url", "must be an XYZ template with {z}, {x} and {y}");
    if (v.optional_string("web_root", c.web_root) && c.web_root->front() != '/')
        v.problem("web_root", "must be an absolute path");
    v.integer("max_connections", c.max_connections, {1, 10000});
    v.integer("max_connections_per_client", c.max_connections_per_client, {1, 10000});
    v.number("idle_timeout_s", c.idle_timeout_s, {1, 3600});
    v.integer("ws_queue_max", c.ws_queue_max, {2, 100000});
    v.string_list("allowed_hosts", c.allowed_hosts, is_bare_host_name,
                  "must be an array of host names",
                  "must be a host name without port, e.g. \"ground-1.lan\"");
}

}  // namespace gimbal::daemon
