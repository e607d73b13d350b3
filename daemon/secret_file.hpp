// Files that hold secrets (command keys, the MQTT password, the MAVLink signing key): they
// must exist and be readable by their owner only, or the daemon refuses to start.
#pragma once

#include <string>
#include <variant>

namespace gimbal::daemon {

// The file's text, or a problem naming the path and the reason ("missing", "readable by
// group or others (mode 0644); chmod 600 it", ...).
std::variant<std::string, std::string> read_private_file(const std::string& path);
inline bool read_ok(const std::variant<std::string, std::string>& r) {
    return r.index() == 0;
}

}  // namespace gimbal::daemon
