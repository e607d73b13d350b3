// Files that hold secrets (command keys, the MQTT password, the MAVLink signing key): they
// must exist and be readable by their owner only, or the daemon refuses to start.
#pragma once

#include <string>
#include <variant>

#include "command/result.hpp"

namespace gimbal::daemon {

// The file's text, or an error whose message names the path and the reason: unavailable
// ("missing", an I/O error), forbidden ("readable by group or others (mode 0644); chmod 600
// it") or bad_request (not a regular file, larger than 64 KiB).
command::Result<std::string> read_secret_file(const std::string& path);

// read_secret_file in the shape config.cpp and mavlink_endpoint.cpp read until they move to
// it: index 0 the text, index 1 the problem.
std::variant<std::string, std::string> read_private_file(const std::string& path);
inline bool read_ok(const std::variant<std::string, std::string>& r) {
    return r.index() == 0;
}

}  // namespace gimbal::daemon
