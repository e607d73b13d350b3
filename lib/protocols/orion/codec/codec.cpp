#include "protocols/orion/codec/codec.hpp"

#include <string>

#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"

namespace gimbal::orion {

std::string to_string(const DecodeError& e) {
    std::string s = e.reason;
    if (!e.field.empty()) s += " at field '" + std::string(e.field) + "'";
    s += " (offset " + std::to_string(e.offset) + ", data length " + std::to_string(e.length) + ")";
    return s;
}

std::string printable(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (const char ch : s) {
        const auto c = static_cast<unsigned char>(ch);
        out.push_back(c >= 0x20 && c < 0x7F ? ch : '?');
    }
    return out;
}

std::string ipv4_to_string(std::uint32_t a) {
    return std::to_string(a >> 24) + "." + std::to_string((a >> 16) & 0xFF) + "." +
           std::to_string((a >> 8) & 0xFF) + "." + std::to_string(a & 0xFF);
}

bool ipv4_from_string(std::string_view s, std::uint32_t& addr) {
    std::uint32_t out = 0;
    int parts = 0;
    std::size_t i = 0;
    while (parts < 4) {
        std::size_t start = i;
        std::uint32_t v = 0;
        while (i < s.size() && s[i] >= '0' && s[i] <= '9' && i - start < 3)
            v = v * 10 + static_cast<std::uint32_t>(s[i++] - '0');
        if (i == start || v > 255) return false;
        out = (out << 8) | v;
        ++parts;
        if (parts < 4) {
            if (i >= s.size() || s[i] != '.') return false;
            ++i;
        }
    }
    if (i != s.size()) return false;
    addr = out;
    return true;
}

std::string_view packet_name(std::uint8_t id) {
    std::string_view name;
    dispatch(id, [&]<class P>() { name = P::name; });
    return name;
}

bool packet_id(std::string_view name, std::uint8_t& id) {
    bool found = false;
    for_each_packet([&]<class P>() {
        if (!found && P::name == name) {
            id = P::id;
            found = true;
        }
    });
    return found;
}

}  // namespace gimbal::orion
