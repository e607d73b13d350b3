#include "command_config.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cctype>
#include <variant>

#include "auth/roles.hpp"
#include "auth/secret.hpp"
#include "secret_file.hpp"

namespace gimbal::daemon {

namespace {

bool valid_key_id(const std::string& id) {
    if (id.empty() || id.size() > 64) return false;
    return std::all_of(id.begin(), id.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.';
    });
}

CommandKey read_key(config::Fields& f) {
    CommandKey key;
    if (f.string("id", key.id, config::Presence::required) && !valid_key_id(key.id))
        f.problem("id", "must be 1 to 64 characters of A-Z a-z 0-9 _ - .");
    if (f.string("secret_file", key.secret_file, config::Presence::required)) {
        const auto text = read_secret_file(key.secret_file);
        if (!text) {
            f.problem("secret_file", text.error().message);
        } else {
            auto secret = gimbal::auth::parse_secret(*text);
            if (auto* bytes = std::get_if<std::vector<std::uint8_t>>(&secret))
                key.secret = std::move(*bytes);
            else
                f.problem("secret_file", key.secret_file + ": " + std::get<std::string>(secret));
        }
    }
    if (const nlohmann::json* roles = f.required("roles")) {
        if (!roles->is_array() || roles->empty()) {
            f.problem("roles", "must be a non-empty array of \"observe\", \"control\", \"laser\"");
        } else {
            for (std::size_t i = 0; i < roles->size(); ++i) {
                const nlohmann::json& r = (*roles)[i];
                if (r.is_string() && gimbal::auth::parse_role(r.get_ref<const std::string&>()))
                    key.roles.push_back(r.get<std::string>());
                else
                    f.problems().add(config::index_path(f.path("roles"), i),
                                     "must be \"observe\", \"control\" or \"laser\"");
            }
        }
    }
    f.finish();
    return key;
}

}  // namespace

void read_allow(config::Fields& f, CommandConfig& c) {
    const auto* allow = f.find("allow");
    if (allow == nullptr) return;
    if (!allow->is_array() || allow->empty()) {
        f.problem("allow", "must be a non-empty array of CIDR blocks such as \"127.0.0.0/8\"");
        return;
    }
    c.allow.clear();
    for (std::size_t i = 0; i < allow->size(); ++i) {
        const nlohmann::json& item = (*allow)[i];
        std::optional<Cidr> cidr;
        if (item.is_string()) cidr = Cidr::parse(item.get_ref<const std::string&>());
        if (cidr)
            c.allow.push_back(*cidr);
        else
            f.problems().add(config::index_path(f.path("allow"), i), "not a CIDR");
    }
}

void read_token(config::Fields& f, CommandConfig& c) {
    const auto* token = f.find("token");
    if (token == nullptr || token->is_null()) return;
    if (!token->is_string() || token->get_ref<const std::string&>().empty() ||
        token->get_ref<const std::string&>().size() > 256)
        f.problem("token", "must be null or a string of 1 to 256 characters");
    else
        c.token = token->get<std::string>();
}

void read_keys(config::Fields& f, CommandConfig& c) {
    const auto* keys = f.find("keys");
    if (keys == nullptr || keys->is_null()) return;
    if (!keys->is_array()) {
        f.problem("keys", "must be an array of {\"id\", \"secret_file\", \"roles\"}");
        return;
    }
    for (std::size_t i = 0; i < keys->size(); ++i) {
        config::Fields k((*keys)[i], config::index_path(f.path("keys"), i), f.problems());
        if (!k.is_object()) continue;
        CommandKey key = read_key(k);
        const bool duplicate =
            std::any_of(c.keys.begin(), c.keys.end(),
                        [&key](const CommandKey& other) { return other.id == key.id; });
        if (duplicate)
            f.problems().add(config::index_path(f.path("keys"), i) + ".id",
                             "duplicate key id \"" + key.id + "\"");
        c.keys.push_back(std::move(key));
    }
}

void check_auth(config::Fields& f, const CommandConfig& c) {
    if (c.token && !c.keys.empty())
        f.problem("keys", "\"token\" and \"keys\" may not both be set: choose one");
    if (c.auth == AuthMode::signed_requests && c.keys.empty())
        f.problem("auth", "\"signed\" needs at least one key in command.keys");
}

nlohmann::json allow_json(const CommandConfig& c) {
    nlohmann::json allow = nlohmann::json::array();
    for (const auto& cidr : c.allow) allow.push_back(cidr.to_string());
    return allow;
}

nlohmann::json keys_json(const CommandConfig& c) {
    // Secrets stay in their files: only where they are is shown.
    nlohmann::json keys = nlohmann::json::array();
    for (const auto& key : c.keys)
        keys.push_back({{"id", key.id}, {"secret_file", key.secret_file}, {"roles", key.roles}});
    return keys;
}

std::optional<Cidr> Cidr::parse(std::string_view text) {
    const auto slash = text.find('/');
    boost::system::error_code ec;
    const auto address = boost::asio::ip::make_address(std::string(text.substr(0, slash)), ec);
    if (ec) return std::nullopt;
    const unsigned max_prefix = address.is_v4() ? 32 : 128;
    unsigned prefix = max_prefix;
    if (slash != std::string_view::npos) {
        const auto digits = text.substr(slash + 1);
        if (digits.empty() || digits.size() > 3 ||
            !std::all_of(digits.begin(), digits.end(),
                         [](char c) { return c >= '0' && c <= '9'; })) {
            return std::nullopt;
        }
        prefix = static_cast<unsigned>(std::stoul(std::string(digits)));
        if (prefix > max_prefix) return std::nullopt;
    }
    Cidr cidr{address, prefix};
    // Clear the host bits so equal blocks compare equal and print canonically.
    if (address.is_v4()) {
        auto bytes = address.to_v4().to_bytes();
        for (std::size_t i = 0; i < bytes.size(); ++i) {
            const unsigned keep = std::min(8u, prefix - std::min(prefix, unsigned(i * 8)));
            bytes[i] = static_cast<unsigned char>(bytes[i] & (0xFF00u >> keep));
        }
        cidr.network = boost::asio::ip::address_v4(bytes);
    } else {
        auto bytes = address.to_v6().to_bytes();
        for (std::size_t i = 0; i < bytes.size(); ++i) {
            const unsigned keep = std::min(8u, prefix - std::min(prefix, unsigned(i * 8)));
            bytes[i] = static_cast<unsigned char>(bytes[i] & (0xFF00u >> keep));
        }
        cidr.network = boost::asio::ip::address_v6(bytes);
    }
    return cidr;
}

bool Cidr::contains(const boost::asio::ip::address& address) const {
    auto candidate = address;
    if (candidate.is_v6() && candidate.to_v6().is_v4_mapped()) {
        candidate = boost::asio::ip::make_address_v4(boost::asio::ip::v4_mapped, candidate.to_v6());
    }
    if (candidate.is_v4() != network.is_v4()) return false;
    auto matches = [this](const auto& a, const auto& b) {
        for (std::size_t i = 0; i < a.size(); ++i) {
            const unsigned keep =
                std::min(8u, prefix_length - std::min(prefix_length, unsigned(i * 8)));
            const unsigned mask = 0xFF00u >> keep;
            if (((a[i] ^ b[i]) & mask) != 0) return false;
        }
        return true;
    };
    if (network.is_v4()) return matches(network.to_v4().to_bytes(), candidate.to_v4().to_bytes());
    return matches(network.to_v6().to_bytes(), candidate.to_v6().to_bytes());
}

std::string Cidr::to_string() const {
    return fmt::format("{}/{}", network.to_string(), prefix_length);
}

std::vector<Cidr> CommandConfig::default_allow() {
    return {*Cidr::parse("127.0.0.0/8"), *Cidr::parse("::1/128")};
}

bool CommandConfig::allowed(const boost::asio::ip::address& source) const {
    return std::any_of(allow.begin(), allow.end(),
                       [&](const Cidr& cidr) { return cidr.contains(source); });
}

}  // namespace gimbal::daemon
