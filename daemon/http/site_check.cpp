#include "site_check.hpp"

#include <algorithm>
#include <boost/asio/ip/address.hpp>
#include <cctype>

namespace gimbald::http {

namespace {

std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

// "name:port", "1.2.3.4:80", "[::1]:8761" or without the port -> the name or address alone.
std::string_view host_name(std::string_view host) {
    if (host.starts_with('[')) {
        const auto close = host.find(']');
        return close == std::string_view::npos ? host : host.substr(1, close - 1);
    }
    const auto colon = host.rfind(':');
    return colon == std::string_view::npos ? host : host.substr(0, colon);
}

bool is_ip_literal(std::string_view name) {
    boost::system::error_code ec;
    boost::asio::ip::make_address(std::string(name), ec);
    return !ec;
}

}  // namespace

std::optional<std::string> host_problem(std::string_view host, const SiteRules& rules) {
    if (host.empty()) return "no Host header";
    std::string name = lower(host_name(host));
    if (name.ends_with('.')) name.pop_back();  // "localhost." is localhost
    if (name.empty()) return "no host name in the Host header";
    if (is_ip_literal(name) || name == "localhost" || name.ends_with(".localhost"))
        return std::nullopt;
    for (const auto& allowed : rules.allowed_hosts)
        if (lower(allowed) == name) return std::nullopt;
    return "Host '" + std::string(host) +
           "' is not an address of gimbald nor listed in http.allowed_hosts (a page served "
           "under another name must not reach it)";
}

std::optional<std::string> origin_problem(std::string_view origin, std::string_view host) {
    if (origin.empty()) return std::nullopt;  // not a browser, or a same-origin GET
    const auto scheme = origin.find("://");
    if (scheme == std::string_view::npos)
        return "cross-site request refused: Origin '" + std::string(origin) + "'";
    std::string_view authority = origin.substr(scheme + 3);
    if (const auto slash = authority.find('/'); slash != std::string_view::npos)
        authority = authority.substr(0, slash);
    std::string expected = lower(host);
    std::string actual = lower(authority);
    // Default ports may be left out of either header.
    const std::string_view scheme_name = origin.substr(0, scheme);
    const std::string port = lower(scheme_name) == "https" ? ":443" : ":80";
    auto strip_default = [&](std::string& s) {
        if (s.ends_with(port)) s.resize(s.size() - port.size());
    };
    strip_default(expected);
    strip_default(actual);
    if (actual == expected) return std::nullopt;
    return "cross-site request refused: Origin '" + std::string(origin) +
           "' is not this server ('" + std::string(host) + "')";
}

}  // namespace gimbald::http
