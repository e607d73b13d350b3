#include "options.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

namespace gimbal_track {

namespace {

constexpr const char* description = R"(NAME
       gimbal-track - the visual tracking process gimbald starts for a gimbal
       whose video has "tracking" configured

SYNOPSIS
       gimbal-track --fd N [--log-level LEVEL]
       gimbal-track --socket PATH [--log-level LEVEL]

DESCRIPTION
       Follows one object in a gimbal's video for gimbald (contract section 20,
       docs/tracking.md). gimbald starts it, restarts it when it dies and talks
       to it over a local SOCK_SEQPACKET socket: gimbald sends "start" (a track
       id, a box in image coordinates, the tracker, the width to scale frames
       to), the video's access units ("au": H.264 or H.265, Annex B, as the
       video input delivers them) and "stop"; gimbal-track answers "hello"
       once, a "box" (position, confidence, tracking or lost) for every frame it
       tracks, "ended" when a track is over and "error" for what gimbald should
       log. Hostile video decoded here, or a tracker fault, cannot stall or
       crash the daemon that holds the laser dead-man.

       Video is decoded (FFmpeg's libavcodec, one thread) only while a track
       runs: with no track, access units are dropped unread and no decoder is
       open. Each decoded frame is scaled to the track's width (the aspect
       kept, never enlarged) and given to the tracker: OpenCV's CSRT or KCF
       with a confidence of gimbal-track's own, loss detection and a
       re-detection search around the position predicted from the object's
       motion. When input arrives faster than it can be tracked, every unit is
       still decoded but only the newest frame is tracked. A track lost for
       its reacquire_s (on the frames' own clock) ends with reason "timeout".

       Nothing is ever sent to the network and nothing listens: the only
       channel is the socket.

OPTIONS)";

constexpr const char* footer = R"(LIMITS
       A datagram of at most 4 MiB and 64 bytes; an access unit of at most
       4 MiB (larger ones are sent in pieces, a datagram being bounded by the
       sender's socket buffer); pictures of at most 4096 x 2304 pixels; no
       single allocation by the decoder above 128 MiB. A refused message is
       counted, logged and answered with "error"; decoding errors are counted
       and decoding resumes at the next key frame.

LOGS
       Standard error, one JSON object per line:
           {"ts":"2026-11-25T10:00:00.123456Z","level":"info",
            "event":"track_start","msg":"...","id":7,...}
       Events: started, track_start, decoder_open, track_lost,
       track_reacquired, track_end (reason, frames, decoder counts),
       decoder_error, decoder_open_failed, track_refused, message_refused,
       stop_ignored (debug), stopping.

EXIT STATUS
       0      gimbald closed the socket, or SIGTERM or SIGINT (a running track
              ends first with reason "stopped"), or --help/--version
       1      bad command line, or the socket cannot be used
       2      the socket failed while running

EXAMPLES
       gimbald runs it as:   gimbal-track --fd 3
       By hand, against a test harness listening on a Unix socket:
           gimbal-track --socket /tmp/track.sock --log-level debug
)";

}  // namespace

ParsedOptions parse_options(int argc, char** argv) {
    Options o;
    int fd = -1;
    std::string socket;
    std::string level = "info";
    bool version = false;

    CLI::App app{description, "gimbal-track"};
    app.footer(footer);
    app.get_formatter()->column_width(30);
    auto* fd_option = app.add_option("--fd", fd, "The connected socket gimbald passed (its number)")
                          ->type_name("N")
                          ->check(CLI::NonNegativeNumber.description(""));
    auto* socket_option =
        app.add_option("--socket", socket, "Connect to the Unix SOCK_SEQPACKET socket at PATH")
            ->type_name("PATH");
    app.add_option("--log-level", level, "debug, info, warn or error")
        ->type_name("LEVEL")
        ->capture_default_str();
    app.add_flag("--version", version, "Print the version and exit");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return {std::nullopt, app.exit(e) == 0 ? 0 : 1};
    }
    if (version) {
        std::cout << "gimbal-track " << GIMBALD_VERSION << "\n";
        return {std::nullopt, 0};
    }
    const auto parsed_level = parse_level(level);
    if (!parsed_level) {
        std::cerr << "gimbal-track: --log-level: debug, info, warn or error\n";
        return {std::nullopt, 1};
    }
    o.log_level = *parsed_level;
    if (*fd_option) o.fd = fd;
    if (*socket_option) o.socket = socket;
    if (o.fd && o.socket) {
        std::cerr << "gimbal-track: --fd and --socket exclude each other\n";
        return {std::nullopt, 1};
    }
    if (!o.fd && !o.socket) {
        std::cerr << "gimbal-track: --fd N or --socket PATH is required\n"
                     "Run with --help for more information.\n";
        return {std::nullopt, 1};
    }
    return {o, 0};
}

}  // namespace gimbal_track
