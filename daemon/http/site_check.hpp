// Browser protections for the HTTP server (docs/http.md "Browsers and other sites"). gimbald
// listens on the operator's own machine, and the operator's browser also visits other sites:
// a page from anywhere can make that browser POST to http://127.0.0.1:8761/api/command or
// open a WebSocket to /api/stream (browsers apply no same-origin rule to either), and a
// DNS-rebinding site can even read the answers. Two header checks close both doors; clients
// that are not browsers (curl, Python, Prometheus) send no Origin and pass unchanged.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gimbald::http {

struct SiteRules {
    // Host names a browser may use to reach gimbald besides IP literals and `localhost`:
    // http.allowed_hosts plus this machine's host name.
    std::vector<std::string> allowed_hosts;
};

// The request's Host header names gimbald (an IP address, localhost, or an allowed name):
// else a DNS-rebinding page is talking to us under its own name. Returns the refusal reason.
std::optional<std::string> host_problem(std::string_view host, const SiteRules& rules);

// For requests that act (POST /api/command, the WebSocket upgrade): an Origin header, when
// present, must name the same host and port as the Host header - the console's own page.
// Returns the refusal reason.
std::optional<std::string> origin_problem(std::string_view origin, std::string_view host);

}  // namespace gimbald::http
