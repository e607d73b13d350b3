// Files the configuration names (the configuration itself, key and password files, TLS files,
// saved state), read so that no file can hang or exhaust the daemon (contract section 14,
// v4): opened without blocking (a FIFO would wait for a writer forever), regular files only
// (/dev/zero never ends), and never more than a limit read.
#pragma once

#include <sys/stat.h>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "command/result.hpp"

namespace gimbal::daemon {

// Extra checks on the opened file's status (e.g. its mode): a reason to refuse it, or none.
using FileCheck = std::function<std::optional<command::Error>(const struct stat&)>;

// The whole file's bytes, or an error whose message names the path and the reason: unavailable
// ("No such file or directory", an I/O error), bad_request ("not a regular file (a FIFO)",
// "larger than 1 MiB") or what `check` says.
command::Result<std::string> read_regular_file(const std::string& path, std::size_t max_bytes,
                                               const FileCheck& check = {});

// Only that it can be opened and is a regular file (certificates handed on to a library).
std::optional<command::Error> check_regular_file(const std::string& path);

// "1 MiB", "64 KiB", "512 bytes".
std::string size_text(std::size_t bytes);

}  // namespace gimbal::daemon
