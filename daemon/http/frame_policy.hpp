// No page of gimbald may be framed by another site (contract section 14, clickjacking):
// every response - pages, API, errors, WebSocket handshakes and their refusals - carries
// X-Frame-Options: DENY and a Content-Security-Policy with frame-ancestors 'none', merged
// into the policy the response already has.
#pragma once

#include <boost/beast/http/fields.hpp>
#include <string>
#include <string_view>

namespace gimbald::http {

// `policy` (a Content-Security-Policy value, possibly empty) with its frame-ancestors
// directive, if any, replaced by frame-ancestors 'none'.
std::string deny_framing(std::string_view policy);

// Sets both headers on a response's fields.
void add_frame_policy(boost::beast::http::fields& fields);

}  // namespace gimbald::http
