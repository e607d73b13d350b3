// What the command layer produces: wire packets to write, or an error with a contract code.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace gimbal::command {

// Error codes of the contract, section 4.
namespace code {
inline constexpr const char* bad_json = "bad_json";
inline constexpr const char* too_large = "too_large";
inline constexpr const char* unknown_cmd = "unknown_cmd";
inline constexpr const char* bad_request = "bad_request";
inline constexpr const char* out_of_range = "out_of_range";
inline constexpr const char* unknown_gimbal = "unknown_gimbal";
inline constexpr const char* unsupported = "unsupported";
inline constexpr const char* unavailable = "unavailable";
inline constexpr const char* link_down = "link_down";
inline constexpr const char* forbidden = "forbidden";
inline constexpr const char* busy = "busy";
inline constexpr const char* rate_limited = "rate_limited";
inline constexpr const char* internal = "internal";
}  // namespace code

struct Error {
    std::string code;
    std::string message;
};

// One packet ready for the link: the full wire frame plus what the reply's `sent` lists.
struct WirePacket {
    std::vector<std::uint8_t> frame;
    nlohmann::json sent;  // Orion {"id": 213, "len": 21}; Viewpro {"frame": "in2", "len": 40}
};

// A laser command the session must track for the dead-man timer and cease-fire rules.
struct LaserIntent {
    std::uint8_t index = 0;
    bool fire = false;
    // The same command with fire = 0, ready to send when the dead-man timer expires, on
    // shutdown or on reconnect.
    std::vector<std::uint8_t> cease_frame;
};

struct Plan {
    std::vector<WirePacket> packets;
    std::optional<LaserIntent> laser;
    nlohmann::json result = nlohmann::json::object();  // extra keys for the reply
};

}  // namespace gimbal::command
