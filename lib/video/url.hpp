// The video URLs of contract section 17, parsed without touching the network:
//   udp://HOST:PORT[?iface=ADDR][&timeout_s=S][&ttl=N]   MPEG-TS over UDP (input or output;
//                                                       a multicast HOST is joined / sent to)
//   rtsp://[user:pass@]HOST[:PORT]/path[?transport=tcp|udp][&timeout_s=S]
//   klv-udp://HOST:PORT[?ttl=N][&iface=ADDR]            one KLV local set per datagram
// HOST is an IPv4 address, [IPv6], or (udp input only) empty / 0.0.0.0 for any. Unknown
// query keys are refused for udp and klv-udp; for rtsp the keys above are taken out and the
// rest stays in the URL handed to the RTSP client (cameras use query strings).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "result/result.hpp"

namespace gimbal::video {

enum class UrlScheme : std::uint8_t { udp, rtsp, klv_udp };

enum class RtspTransport : std::uint8_t { automatic, tcp, udp };

struct VideoUrl {
    UrlScheme scheme = UrlScheme::udp;
    std::string text;  // as given
    std::string host;  // without brackets; empty = any (udp input)
    std::uint16_t port = 0;
    std::optional<int> ttl;           // 1..255
    std::string iface;                // multicast interface address
    std::optional<double> timeout_s;  // no data for this long = disconnected
    RtspTransport transport = RtspTransport::automatic;
    std::string rtsp_url;  // rtsp: the URL for the RTSP client, our own keys removed
};

// The URL, or bad_request saying why not.
Result<VideoUrl> parse_video_url(std::string_view text);

// RTSP redirects and credentials (contract section 14 v4): the "host:port" an rtsp:// URL
// names (host lower-cased, an IPv6 address in brackets, port 554 when none is given), so two
// URLs can be compared; nullopt when it is not an rtsp:// URL with a host.
std::optional<std::string> rtsp_authority(std::string_view url);
// The URL without its "user[:pass]@" part.
std::string without_userinfo(std::string_view url);
// The URL with its password shown as "***" (logs, STATE): "rtsp://admin:***@10.0.0.9/live".
std::string redact_userinfo(std::string_view url);

std::string_view to_string(UrlScheme scheme);

}  // namespace gimbal::video
