#include "protocols/siyi/codec/json.hpp"

#include <cstdio>

namespace gimbal::siyi {

std::string version_string(std::uint32_t word) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%u.%u.%u", (word >> 16) & 0xFFu, (word >> 8) & 0xFFu,
                  word & 0xFFu);
    return buf;
}

std::string printable(std::string_view bytes) {
    std::string out;
    out.reserve(bytes.size());
    for (const char c : bytes) {
        const auto b = static_cast<unsigned char>(c);
        if (b >= 0x20 && b < 0x7F) {
            out.push_back(c);
        } else {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02X", b);
            out += hex;
        }
    }
    return out;
}

nlohmann::json to_json(const ToGimbal& m) {
    return std::visit([](const auto& msg) { return to_json(msg); }, m);
}

nlohmann::json to_json(const FromGimbal& m) {
    return std::visit([](const auto& msg) { return to_json(msg); }, m);
}

nlohmann::json frame_to_json(const Frame& frame, Direction direction) {
    nlohmann::json out = nlohmann::json::object();
    const auto describe = [&](const auto& decoded) {
        if (decoded.ok()) {
            out = to_json(decoded.value);
        } else {
            out["error"] = to_string(decoded.error);
            out["length"] = frame.data.size;
        }
    };
    if (direction == Direction::to_gimbal)
        describe(decode_to_gimbal(frame));
    else
        describe(decode_from_gimbal(frame));
    out["cmd"] = frame.cmd;
    out["ctrl"] = frame.ctrl;
    out["seq"] = frame.seq;
    return out;
}

}  // namespace gimbal::siyi
