#include "video/source_pin.hpp"

#include <charconv>

namespace gimbald::video {

namespace asio = boost::asio;
using asio::ip::udp;

namespace {

// An IPv4 sender seen through a dual-stack socket is ::ffff:a.b.c.d: compare it as IPv4.
asio::ip::address plain(const asio::ip::address& a) {
    if (a.is_v6() && a.to_v6().is_v4_mapped())
        return asio::ip::make_address_v4(asio::ip::v4_mapped, a.to_v6());
    return a;
}

std::optional<asio::ip::address> address(std::string_view text) {
    boost::system::error_code ec;
    const auto a = asio::ip::make_address(std::string(text), ec);
    if (ec) return std::nullopt;
    return plain(a);
}

std::optional<std::uint16_t> port_number(std::string_view text) {
    unsigned v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || end != text.data() + text.size() || v == 0 || v > 65535)
        return std::nullopt;
    return static_cast<std::uint16_t>(v);
}

}  // namespace

std::optional<SourceSpec> parse_source(std::string_view text, std::string& error) {
    std::string_view host = text;
    std::string_view port;
    if (!text.empty() && text.front() == '[') {
        const std::size_t close = text.find(']');
        if (close == std::string_view::npos ||
            (close + 1 < text.size() && text[close + 1] != ':')) {
            error = "expected ADDR, ADDR:PORT, [IPv6] or [IPv6]:PORT";
            return std::nullopt;
        }
        host = text.substr(1, close - 1);
        if (close + 1 < text.size()) port = text.substr(close + 2);
    } else if (const std::size_t colon = text.find(':');
               colon != std::string_view::npos &&
               text.find(':', colon + 1) == std::string_view::npos) {
        host = text.substr(0, colon);  // one colon: IPv4:PORT (more: a bare IPv6 address)
        port = text.substr(colon + 1);
    }
    SourceSpec spec;
    const auto a = address(host);
    if (!a) {
        error = "\"" + std::string(host) + "\" is not a numeric IP address";
        return std::nullopt;
    }
    spec.address = *a;
    if (!port.empty() || (!text.empty() && text.back() == ':')) {
        spec.port = port_number(port);
        if (!spec.port) {
            error = "port must be 1..65535";
            return std::nullopt;
        }
    }
    return spec;
}

std::string to_string(const udp::endpoint& endpoint) {
    const auto a = plain(endpoint.address());
    const std::string host = a.is_v6() ? "[" + a.to_string() + "]" : a.to_string();
    return host + ":" + std::to_string(endpoint.port());
}

SourcePin::SourcePin(std::optional<SourceSpec> configured, Clock::duration silence)
    : configured_(std::move(configured)), silence_(silence) {}

SourcePin::Verdict SourcePin::check(const udp::endpoint& sender, Clock::time_point now) {
    const udp::endpoint from(plain(sender.address()), sender.port());
    if (configured_) {
        const bool match = from.address() == configured_->address &&
                           (!configured_->port || *configured_->port == from.port());
        if (!match) {
            ++foreign_;
            return Verdict::foreign;
        }
        current_ = from;
        return Verdict::accepted;
    }
    if (current_ && from == *current_) {
        last_ = now;
        return Verdict::accepted;
    }
    if (current_ && now - last_ < silence_) {
        ++foreign_;
        return Verdict::foreign;
    }
    current_ = from;
    last_ = now;
    return Verdict::pinned;
}

}  // namespace gimbald::video
