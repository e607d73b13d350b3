// What the command layer produces: wire packets to write (Plan), with the laser it fires.
// Its results and errors are gimbald's one result type (lib/result), named here as the
// command layer always spelt them (command::Error, command::code::bad_request).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "result/result.hpp"

namespace gimbal::command {

using gimbal::Error;
using gimbal::error_code_names;
using gimbal::ErrorCode;
using gimbal::parse_error_code;
using gimbal::Result;
using gimbal::Status;
using gimbal::to_string;
namespace code = gimbal::code;

// One packet ready for the link: the full wire frame plus what the reply's `sent` lists.
struct WirePacket {
    std::vector<std::uint8_t> frame;
    nlohmann::json sent;  // the protocol's description of it, e.g. {"id": 213, "len": 21}
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
