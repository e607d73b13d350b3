#include "link/link_config.hpp"

#include <boost/asio/ip/address.hpp>

#include <fmt/format.h>
#include <algorithm>
#include <array>

namespace gimbal::daemon {

namespace {

constexpr std::array<std::uint32_t, 22> baud_rates = {
    1200,   1800,   2400,   4800,    9600,    19200,   38400,   57600,   115200,  230400,  460800,
    500000, 576000, 921600, 1000000, 1152000, 1500000, 2000000, 2500000, 3000000, 3500000, 4000000};

std::string baud_message() {
    std::string rates;
    for (auto rate : baud_rates) rates += (rates.empty() ? "" : ", ") + std::to_string(rate);
    return "must be one of " + rates;
}

template <class Section>
Link read_as(config::Fields& f) {
    Section section;
    fields(f, section);
    return section;
}

}  // namespace

std::span<const std::uint32_t> standard_baud_rates() {
    return baud_rates;
}

std::string_view link_type(const Link& link) {
    static constexpr std::string_view names[] = {"tcp", "serial", "sim", "udp"};
    return names[link.index()];
}

std::string describe(const Link& link) {
    if (const auto* tcp = std::get_if<TcpLink>(&link)) {
        if (tcp->discover())
            return fmt::format("discover via {}:{}", tcp->discover_address, tcp->discover_port);
        if (tcp->host.find(':') != std::string::npos)
            return fmt::format("[{}]:{}", tcp->host, tcp->port);
        return fmt::format("{}:{}", tcp->host, tcp->port);
    }
    if (const auto* serial = std::get_if<SerialLink>(&link))
        return fmt::format("{}@{}", serial->device, serial->baud);
    if (const auto* udp = std::get_if<UdpLink>(&link)) {
        if (udp->host.find(':') != std::string::npos)
            return fmt::format("udp [{}]:{}", udp->host, udp->port);
        return fmt::format("udp {}:{}", udp->host, udp->port);
    }
    return "sim";
}

std::optional<Link> read_link(config::Fields& f) {
    std::string type;
    if (!f.choice("type", type, {"tcp", "serial", "sim", "udp"}, config::Presence::required)) {
        f.keep_unknown_keys();  // which keys belong here depends on the type
        return std::nullopt;
    }
    if (type == "tcp") return read_as<TcpLink>(f);
    if (type == "serial") return read_as<SerialLink>(f);
    if (type == "udp") return read_as<UdpLink>(f);
    return SimLink{};
}

nlohmann::json write_link(const Link& link) {
    return std::visit(
        [&link](const auto& section) {
            nlohmann::json out = config::write(section);
            out["type"] = std::string(link_type(link));
            return out;
        },
        link);
}

void read_baud(config::Fields& f, std::string_view key, std::uint32_t& out) {
    const auto* value = f.required(key);
    if (value == nullptr) return;
    if (value->is_number_unsigned() || value->is_number_integer()) {
        const auto rate = value->get<std::int64_t>();
        for (auto standard : baud_rates) {
            if (rate == standard) {
                out = standard;
                return;
            }
        }
    }
    f.problem(key, baud_message());
}

void read_device(config::Fields& f, std::string_view key, std::string& out) {
    if (!f.string(key, out, config::Presence::required)) return;
    if (out.empty() || out.front() != '/')
        f.problem(key, "must be an absolute path such as /dev/ttyUSB0");
}

bool valid_host(const std::string& host) {
    const bool has_space =
        std::any_of(host.begin(), host.end(), [](char c) { return c <= ' ' || c > '~'; });
    return !host.empty() && host.size() <= 253 && !has_space;
}

void check_reconnect(config::Fields& f, double min_s, double max_s) {
    if (max_s < min_s)
        f.problem("reconnect_max_s",
                  fmt::format("must not be less than reconnect_min_s ({:g})", min_s));
}

void read_discover_address(config::Fields& f, std::string& out) {
    const auto* value = f.find("discover_address");
    if (value == nullptr) return;
    boost::system::error_code ec;
    boost::asio::ip::address address;
    if (value->is_string()) address = boost::asio::ip::make_address(value->get<std::string>(), ec);
    if (!value->is_string() || ec)
        f.problem("discover_address", "must be an IPv4 or IPv6 address");
    else if (!address.is_v4())
        f.problem("discover_address", "must be an IPv4 address");
    else
        out = address.to_string();
}

}  // namespace gimbal::daemon
