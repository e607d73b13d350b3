// gimbal-track's command line.
#pragma once

#include <optional>
#include <string>

#include "json_log.hpp"

namespace gimbal_track {

struct Options {
    std::optional<int> fd;              // --fd N: the socket gimbald passed
    std::optional<std::string> socket;  // --socket PATH: connect to it
    Level log_level = Level::info;
};

struct ParsedOptions {
    std::optional<Options> options;  // null: exit with `exit_code` (help, version, errors)
    int exit_code = 0;
};

ParsedOptions parse_options(int argc, char** argv);

}  // namespace gimbal_track
