#include "video/url.hpp"

#include <cctype>
#include <charconv>
#include <vector>

namespace gimbal::video {

namespace {

struct Query {
    std::string key;
    std::string value;
};

std::vector<Query> split_query(std::string_view q) {
    std::vector<Query> out;
    while (!q.empty()) {
        const std::size_t amp = q.find('&');
        const std::string_view item = q.substr(0, amp);
        const std::size_t eq = item.find('=');
        out.push_back({std::string(item.substr(0, eq)),
                       eq == std::string_view::npos ? "" : std::string(item.substr(eq + 1))});
        q = amp == std::string_view::npos ? std::string_view{} : q.substr(amp + 1);
    }
    return out;
}

template <class T>
std::optional<T> number(std::string_view s) {
    T v{};
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size()) return std::nullopt;
    return v;
}

std::optional<double> seconds(std::string_view s) {
    // from_chars for double is in libstdc++ 11+; keep to digits and one dot.
    if (s.empty() || s.size() > 12 || s.find_first_not_of("0123456789.") != std::string_view::npos)
        return std::nullopt;
    const double v = std::stod(std::string(s));
    if (!(v > 0) || v > 3600) return std::nullopt;
    return v;
}

// "HOST:PORT" or "[V6]:PORT"; the port is required.
bool host_port(std::string_view hp, VideoUrl& url, std::string& error) {
    std::string_view host;
    std::string_view port;
    if (!hp.empty() && hp[0] == '[') {
        const std::size_t close = hp.find(']');
        if (close == std::string_view::npos || close + 1 >= hp.size() || hp[close + 1] != ':') {
            error = "expected [IPv6]:PORT";
            return false;
        }
        host = hp.substr(1, close - 1);
        port = hp.substr(close + 2);
    } else {
        const std::size_t colon = hp.rfind(':');
        if (colon == std::string_view::npos) {
            error = "missing :PORT";
            return false;
        }
        host = hp.substr(0, colon);
        port = hp.substr(colon + 1);
        if (host.find(':') != std::string_view::npos) {
            error = "an IPv6 address goes in brackets: [ADDR]:PORT";
            return false;
        }
    }
    const auto p = number<unsigned>(port);
    if (!p || *p == 0 || *p > 65535) {
        error = "port must be 1..65535";
        return false;
    }
    url.host = std::string(host);
    url.port = static_cast<std::uint16_t>(*p);
    return true;
}

Error fail(std::string error) {
    return {code::bad_request, std::move(error)};
}

}  // namespace

std::string_view to_string(UrlScheme scheme) {
    switch (scheme) {
        case UrlScheme::udp:
            return "udp";
        case UrlScheme::rtsp:
            return "rtsp";
        case UrlScheme::klv_udp:
            return "klv-udp";
    }
    return "udp";
}

Result<VideoUrl> parse_video_url(std::string_view text) {
    VideoUrl url;
    url.text = std::string(text);
    const std::size_t sep = text.find("://");
    if (sep == std::string_view::npos) return fail("expected udp://, rtsp:// or klv-udp://");
    const std::string_view scheme = text.substr(0, sep);
    if (scheme == "udp") {
        url.scheme = UrlScheme::udp;
    } else if (scheme == "rtsp") {
        url.scheme = UrlScheme::rtsp;
    } else if (scheme == "klv-udp") {
        url.scheme = UrlScheme::klv_udp;
    } else {
        return fail("unknown scheme '" + std::string(scheme) + "' (udp, rtsp or klv-udp)");
    }
    std::string_view rest = text.substr(sep + 3);
    const std::size_t qmark = rest.find('?');
    const std::string_view query = qmark == std::string_view::npos ? "" : rest.substr(qmark + 1);
    rest = rest.substr(0, qmark);

    std::string kept;  // rtsp query items that are not ours
    for (const Query& q : split_query(query)) {
        if (q.key == "timeout_s") {
            url.timeout_s = seconds(q.value);
            if (!url.timeout_s) return fail("timeout_s must be a number of seconds, 0 < s <= 3600");
        } else if (q.key == "ttl" && url.scheme != UrlScheme::rtsp) {
            const auto ttl = number<int>(q.value);
            if (!ttl || *ttl < 1 || *ttl > 255) return fail("ttl must be 1..255");
            url.ttl = ttl;
        } else if (q.key == "iface" && url.scheme != UrlScheme::rtsp) {
            if (q.value.empty()) return fail("iface needs an address");
            url.iface = q.value;
        } else if (q.key == "transport" && url.scheme == UrlScheme::rtsp) {
            if (q.value == "tcp") {
                url.transport = RtspTransport::tcp;
            } else if (q.value == "udp") {
                url.transport = RtspTransport::udp;
            } else {
                return fail("transport must be tcp or udp");
            }
        } else if (url.scheme == UrlScheme::rtsp) {
            kept += (kept.empty() ? "" : "&") + q.key + (q.value.empty() ? "" : "=" + q.value);
        } else {
            return fail("unknown option '" + q.key + "'");
        }
    }

    if (url.scheme == UrlScheme::rtsp) {
        const std::size_t slash = rest.find('/');
        std::string_view authority = rest.substr(0, slash);
        if (const std::size_t at = authority.rfind('@'); at != std::string_view::npos)
            authority = authority.substr(at + 1);
        if (authority.empty()) return fail("rtsp:// needs a host");
        std::string error;
        if (authority.find(':') != std::string_view::npos && authority.back() != ']') {
            if (!host_port(authority, url, error)) return fail(error);
        } else {
            url.host = std::string(
                authority.front() == '[' ? authority.substr(1, authority.size() - 2) : authority);
            url.port = 554;
        }
        url.rtsp_url = "rtsp://" + std::string(rest) + (kept.empty() ? "" : "?" + kept);
        return url;
    }
    std::string error;
    if (!host_port(rest, url, error)) return fail(error);
    if (url.host.empty() && url.scheme == UrlScheme::klv_udp)
        return fail("klv-udp:// needs a host");
    return url;
}

namespace {

// Where the authority of a URL with "://" starts and ends, and its '@' (npos when none).
struct Authority {
    std::size_t begin = std::string_view::npos;
    std::size_t end = std::string_view::npos;
    std::size_t at = std::string_view::npos;
};

Authority find_authority(std::string_view url) {
    Authority a;
    const std::size_t sep = url.find("://");
    if (sep == std::string_view::npos) return a;
    a.begin = sep + 3;
    a.end = url.find_first_of("/?#", a.begin);
    if (a.end == std::string_view::npos) a.end = url.size();
    const std::size_t at = url.substr(a.begin, a.end - a.begin).rfind('@');
    if (at != std::string_view::npos) a.at = a.begin + at;
    return a;
}

}  // namespace

std::optional<std::string> rtsp_authority(std::string_view url) {
    const std::size_t sep = url.find("://");
    if (sep == std::string_view::npos) return std::nullopt;
    std::string scheme(url.substr(0, sep));
    for (char& c : scheme) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (scheme != "rtsp") return std::nullopt;
    const Authority a = find_authority(url);
    std::string_view hp = url.substr(a.begin, a.end - a.begin);
    if (a.at != std::string_view::npos) hp = url.substr(a.at + 1, a.end - a.at - 1);
    std::string_view host = hp;
    std::string_view port;
    if (!hp.empty() && hp.front() == '[') {
        const std::size_t close = hp.find(']');
        if (close == std::string_view::npos) return std::nullopt;
        host = hp.substr(0, close + 1);
        if (close + 1 < hp.size()) {
            if (hp[close + 1] != ':') return std::nullopt;
            port = hp.substr(close + 2);
        }
    } else if (const std::size_t colon = hp.find(':'); colon != std::string_view::npos) {
        host = hp.substr(0, colon);
        port = hp.substr(colon + 1);
    }
    if (host.empty() || host == "[]") return std::nullopt;
    unsigned port_number = 554;
    if (!port.empty()) {
        const auto p = number<unsigned>(port);
        if (!p || *p == 0 || *p > 65535) return std::nullopt;
        port_number = *p;
    }
    std::string out(host);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out + ":" + std::to_string(port_number);
}

std::string without_userinfo(std::string_view url) {
    const Authority a = find_authority(url);
    if (a.at == std::string_view::npos) return std::string(url);
    return std::string(url.substr(0, a.begin)) + std::string(url.substr(a.at + 1));
}

std::string redact_userinfo(std::string_view url) {
    const Authority a = find_authority(url);
    if (a.at == std::string_view::npos) return std::string(url);
    const std::string_view userinfo = url.substr(a.begin, a.at - a.begin);
    const std::size_t colon = userinfo.find(':');
    if (colon == std::string_view::npos) return std::string(url);
    return std::string(url.substr(0, a.begin + colon + 1)) + "***" + std::string(url.substr(a.at));
}

}  // namespace gimbal::video
