#include "frame_policy.hpp"

#include <boost/beast/core/string.hpp>
#include <boost/beast/http/field.hpp>
#include <cctype>

namespace gimbald::http {

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

// Directive names are case-insensitive (CSP Level 3, section 2.2).
bool names_frame_ancestors(std::string_view directive) {
    constexpr std::string_view name = "frame-ancestors";
    if (directive.size() < name.size()) return false;
    for (std::size_t i = 0; i < name.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(directive[i])) != name[i]) return false;
    return directive.size() == name.size() ||
           std::isspace(static_cast<unsigned char>(directive[name.size()]));
}

}  // namespace

std::string deny_framing(std::string_view policy) {
    std::string out;
    while (!policy.empty()) {
        const auto semicolon = policy.find(';');
        const auto directive = trim(policy.substr(0, semicolon));
        policy =
            semicolon == std::string_view::npos ? std::string_view{} : policy.substr(semicolon + 1);
        if (directive.empty() || names_frame_ancestors(directive)) continue;
        out.append(directive);
        out.append("; ");
    }
    out.append("frame-ancestors 'none'");
    return out;
}

void add_frame_policy(boost::beast::http::fields& fields) {
    using boost::beast::http::field;
    fields.set(field::x_frame_options, "DENY");
    // Beast has no field enum for Content-Security-Policy: set by name.
    const boost::beast::string_view csp = "Content-Security-Policy";
    const auto existing = fields[csp];
    fields.set(csp, deny_framing(std::string_view(existing.data(), existing.size())));
}

}  // namespace gimbald::http
