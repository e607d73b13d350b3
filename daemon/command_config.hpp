// `command` (contract sections 4 and 10, docs/configuration.md): the UDP command socket, who
// may use it (allow, token) and signed requests (auth, keys, max_skew_s, rate_limit). Declared
// once here and read and written by the generic reader (lib/config/fields.hpp).
#pragma once

#include <array>
#include <boost/asio/ip/address.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "address_field.hpp"
#include "config/fields.hpp"

namespace gimbal::daemon {

// An address block such as 192.168.1.0/24 or ::1/128.
struct Cidr {
    boost::asio::ip::address network;  // host bits cleared
    unsigned prefix_length = 0;

    // "a.b.c.d/n" (n 0..32), "v6addr/n" (n 0..128), or a bare address (a single host).
    // Host bits are cleared: "127.0.0.1/8" is 127.0.0.0/8.
    static std::optional<Cidr> parse(std::string_view text);
    // IPv4-mapped IPv6 sources (::ffff:a.b.c.d, seen on dual-stack sockets) match IPv4 blocks.
    bool contains(const boost::asio::ip::address& address) const;
    std::string to_string() const;
    bool operator==(const Cidr&) const = default;
};

// command.auth (contract section 10).
enum class AuthMode { none, signed_requests };

// One key of command.keys; `secret` is read from `secret_file` when the file is loaded.
struct CommandKey {
    std::string id;
    std::string secret_file;
    std::vector<std::string> roles;  // observe, control, laser
    std::vector<std::uint8_t> secret;
    bool operator==(const CommandKey&) const = default;
};

struct RateLimitConfig {
    double per_source_hz = 200;
    double burst = 400;
    bool operator==(const RateLimitConfig&) const = default;
};

struct CommandConfig {
    boost::asio::ip::address bind = boost::asio::ip::make_address_v4("127.0.0.1");
    std::uint16_t port = 8760;
    std::vector<Cidr> allow = default_allow();
    std::optional<std::string> token;
    unsigned max_subscribers = 64;
    unsigned max_subscribers_per_host = 16;  // one source address may not fill the table
    AuthMode auth = AuthMode::none;
    std::vector<CommandKey> keys;
    double max_skew_s = 30;
    RateLimitConfig rate_limit;

    // True when a datagram from `source` may be answered (it lies in one of `allow`).
    bool allowed(const boost::asio::ip::address& source) const;
    static std::vector<Cidr> default_allow();
    bool operator==(const CommandConfig&) const = default;
};

inline constexpr std::array<config::Named<AuthMode>, 2> auth_mode_names{
    {{"none", AuthMode::none}, {"signed", AuthMode::signed_requests}}};

// Reading's own steps: the CIDR list, the token's length, the keys with their secret files
// read now, and the checks across keys.
void read_allow(config::Fields& f, CommandConfig& c);
void read_token(config::Fields& f, CommandConfig& c);
void read_keys(config::Fields& f, CommandConfig& c);
void check_auth(config::Fields& f, const CommandConfig& c);
// Written back: the blocks as text, the keys without their secrets (only where they are).
nlohmann::json allow_json(const CommandConfig& c);
nlohmann::json keys_json(const CommandConfig& c);

template <class V>
void fields(V& v, CommandConfig& c) {
    address(v, "bind", c.bind);
    v.integer("port", c.port, {1, 65535});
    if constexpr (V::reading) {
        read_allow(v, c);
        read_token(v, c);
    } else {
        v.set_json("allow", allow_json(c));
        v.optional_string("token", c.token);
    }
    v.integer("max_subscribers", c.max_subscribers, {1, 1024});
    v.integer("max_subscribers_per_host", c.max_subscribers_per_host, {1, 1024});
    v.choice("auth", c.auth, auth_mode_names);
    if constexpr (V::reading)
        read_keys(v, c);
    else
        v.set_json("keys", keys_json(c));
    v.number("max_skew_s", c.max_skew_s, {1, 3600});
    v.section("rate_limit", [&](auto& rate) {
        rate.number("per_source_hz", c.rate_limit.per_source_hz, {0.1, 100000});
        rate.number("burst", c.rate_limit.burst, {1, 1000000});
    });
    if constexpr (V::reading) check_auth(v, c);
}

}  // namespace gimbal::daemon
