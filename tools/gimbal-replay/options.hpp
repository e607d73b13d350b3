// gimbal-replay's command line.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace gimbal_replay {

struct ReplayOptions {
    std::vector<std::string> files;  // one recording: its files in order
    std::string gimbal;              // empty: the only gimbal in the recording
    double speed = 1.0;
    bool tcp = true;
    std::string bind = "127.0.0.1";
    std::uint16_t port = 8747;  // 0: any free port (printed)
    bool pty = false;
    std::string pty_link;  // symlink to the pty device, if set
    bool loop = false;
    bool hold = false;  // keep serving (silently) after the end
    double progress_every_s = 5.0;
    std::string video;  // udp://HOST:PORT: also send the gimbal's recorded video there
};

struct ParsedOptions {
    std::optional<ReplayOptions> options;
    int exit_status = 0;
};
// --help and --version: exit 0; a bad command line: 1, with the message printed.
ParsedOptions parse_options(int argc, char** argv);

}  // namespace gimbal_replay
