// Files that hold secrets (command keys, the MQTT password, the MAVLink signing key): they
// must exist and be readable by their owner only, or the daemon refuses to start.
#pragma once

#include <string>

#include "command/result.hpp"

namespace gimbal::daemon {

// The file's text, or an error whose message names the path and the reason: unavailable
// ("missing", an I/O error), forbidden ("readable by group or others (mode 0644); chmod 600
// it") or bad_request (not a regular file, larger than 64 KiB).
command::Result<std::string> read_secret_file(const std::string& path);

}  // namespace gimbal::daemon
