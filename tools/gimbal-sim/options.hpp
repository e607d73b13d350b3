// gimbal-sim's command line: what to serve, where, which faults to inject, and the simulated
// gimbal's own settings (the shared ones, and each protocol's flags from its registry entry).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "protocols/registry.hpp"
#include "video_options.hpp"

namespace gimbal_sim {

struct ToolOptions {
    std::string protocol;  // a registry name; the first protocol when not given

    bool tcp = true;
    std::string bind = "127.0.0.1";
    std::uint16_t port = 8747;  // 0: any free port (printed)

    std::optional<std::uint16_t> udp_port;  // --udp: serve datagrams (0: any free port)
    bool pty = false;
    std::string pty_link;  // symlink to the pty device, if set

    bool discovery = true;  // only for a protocol with discovery
    std::uint16_t discovery_port = 8745;
    std::uint16_t discovery_reply_port = 8746;  // 0: the request's source port

    // Faults, for tests of the receiving side.
    double drop_after_s = 0;  // close each TCP client this long after it connected; 0 = never
    double corrupt_fraction = 0;
    unsigned junk_every = 0;
    double stall_after_s = 0;          // go silent this long after a client connects ...
    double stall_for_s = 0;            // ... for this long; 0 = never
    double stall_reading_after_s = 0;  // stop reading this long after a client connects ...
    double stall_reading_for_s = 0;    // ... for this long; 0 = never
    unsigned read_baud = 0;            // read no faster than a serial line at this rate

    std::string rx_log;     // JSON lines of every valid packet received
    std::string write_dem;  // write the simulator's terrain as a GeoTIFF here, then exit
    double tick_s = 0.01;

    gimbal::protocols::SimScenario scenario;  // the model: clock, seed, settings, own flags
    VideoToolOptions video;                   // --video (video_options.hpp)

    const gimbal::protocols::Entry& entry() const { return *gimbal::protocols::find(protocol); }
};

// Parses argv. Returns the options, or the exit status when the program should stop now
// (--help, --version: 0; a bad command line: 1, with the message printed).
struct ParsedOptions {
    std::optional<ToolOptions> options;
    int exit_status = 0;
};
ParsedOptions parse_options(int argc, char** argv);

}  // namespace gimbal_sim
