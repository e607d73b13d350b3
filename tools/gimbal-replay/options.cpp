#include "options.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "video/url.hpp"

namespace gimbal_replay {

namespace {

constexpr const char* description = R"(NAME
       gimbal-replay - play a gimbal's side of a gimbald recording back as a
       simulated gimbal

SYNOPSIS
       gimbal-replay FILE... [--gimbal NAME] [--speed N] [--tcp PORT] [--pty [PATH]]
                     [--no-tcp] [--loop] [--hold] [--video udp://HOST:PORT]

DESCRIPTION
       Reads a pcapng recording written by gimbald (the "record" configuration,
       docs/recording.md) and sends the bytes one gimbal sent during the
       flight - the inbound PDUs of its interface "gimbal:NAME", in order - to
       whoever connects, as gimbal-sim does: a TCP server (one client at a time;
       a new client replaces the old one) and/or a pseudo-terminal. The recorded
       spacing between packets is kept, divided by --speed. A gimbald connected
       to it decodes the same packets and so rebuilds the STATE it had in flight
       (telemetry, mode, versions, ...); see docs/replay-export.md.

       Playback starts when the first controller connects (TCP client or the
       pty opened). It then runs on like a real gimbal: bytes due while no
       controller is connected are dropped. Bytes the controller sends are read
       and ignored: a recording cannot answer new commands.

       Nothing in the packets is rewritten: GPS time, system time and every
       other field are the recorded ones. Only gimbald's own clock-derived
       values (age_s, stale, last_rx_age_s) follow the replay's pace.

       With --video, the gimbal's recorded video (its interface "video:NAME":
       the MPEG-TS datagrams gimbald received, KLV included) goes to that UDP
       address on the same clock as the gimbal's bytes, so a gimbald with
       "video": {"input": "udp://..."} sees the flight's picture and metadata
       again, in step with its telemetry. Each datagram is sent as recorded.

       Several FILEs are played as one recording, in the order given (gimbald
       rotates files: gimbal-replay /var/lib/gimbald/recordings/gimbald-20261125T*
       plays a flight that spans several). A file cut short by a crash plays up
       to its last complete block (with a warning); so does one damaged in the
       middle.
)";

constexpr const char* footer = R"(OUTPUT
       On standard output, one line per endpoint as soon as it is ready:
           tcp: 127.0.0.1:8747
           pty: /dev/pts/5
       then, when playback starts and ends:
           playing: gimbal main (orion), 3012 packets, 30.0 s recorded, speed 10
           done: 3012 packets, 412345 bytes, 30.0 s recorded in 3.0 s
       Progress (every 5 s), warnings and clients connecting go to standard error.

EXIT STATUS
       0 played to the end (or stopped by SIGINT or SIGTERM, or --help);
       1 bad command line, or the file is not a readable recording or holds no
       such gimbal; 2 runtime failure (the port cannot be bound, no pty).

EXAMPLES
       gimbal-replay flight.pcapng
       gimbal-replay flight.pcapng --gimbal nose --speed 10 --tcp 0
       gimbal-replay flight.pcapng --no-tcp --pty /tmp/orion --loop
       gimbal-replay flight.pcapng --video udp://127.0.0.1:15004
)";

}  // namespace

ParsedOptions parse_options(int argc, char** argv) {
    ReplayOptions o;
    bool no_tcp = false;
    bool version = false;

    CLI::App app{description, "gimbal-replay"};
    app.footer(footer);
    app.get_formatter()->column_width(30);
    // Not required() here: --version needs no FILE; checked after parsing.
    app.add_option("FILE", o.files, "Recording (pcapng) to play; several: in this order")
        ->type_name("");
    app.add_option("--gimbal", o.gimbal,
                   "Gimbal to play (its interface gimbal:NAME); needed when the recording "
                   "holds several")
        ->type_name("NAME");
    app.add_option("--speed", o.speed, "Playback speed factor, 0.001..1000 (2 = twice as fast)")
        ->type_name("N")
        ->check(CLI::Range(0.001, 1000.0).description(""))
        ->capture_default_str();
    app.add_option("--bind", o.bind, "Address the TCP server listens on")
        ->type_name("ADDRESS")
        ->capture_default_str();
    app.add_option("--tcp", o.port, "TCP port; 0 picks a free one (printed)")
        ->type_name("PORT")
        ->capture_default_str();
    app.add_flag("--no-tcp", no_tcp, "Do not serve TCP");
    app.add_option("--pty", o.pty_link,
                   "Serve a pseudo-terminal (prints its device path); with PATH, also make "
                   "a symlink there")
        ->type_name("[PATH]")
        ->expected(0, 1);
    app.add_flag("--loop", o.loop, "Start again from the beginning at the end, forever");
    app.add_flag("--hold", o.hold, "At the end, keep the endpoints open (silent) until stopped");
    app.add_option("--progress-every", o.progress_every_s,
                   "Seconds between progress lines; 0 = none")
        ->type_name("S")
        ->check(CLI::NonNegativeNumber.description(""))
        ->capture_default_str();
    app.add_option("--video", o.video,
                   "Send the gimbal's recorded video (MPEG-TS with its KLV) to udp://HOST:PORT")
        ->type_name("URL");
    app.add_flag("--version", version, "Print the version and exit");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return {std::nullopt, app.exit(e) == 0 ? 0 : 1};
    }
    if (version) {
        std::cout << "gimbal-replay " << GIMBALD_VERSION << "\n";
        return {std::nullopt, 0};
    }
    if (o.files.empty()) {
        std::cerr << "gimbal-replay: FILE is required\nRun with --help for more information.\n";
        return {std::nullopt, 1};
    }
    o.tcp = !no_tcp;
    o.pty = app.count("--pty") > 0;
    if (!o.tcp && !o.pty) {
        std::cerr << "gimbal-replay: nothing to serve: --no-tcp needs --pty\n";
        return {std::nullopt, 1};
    }
    if (!o.video.empty()) {
        const auto url = gimbal::video::parse_video_url(o.video);
        if (!url || url->scheme != gimbal::video::UrlScheme::udp || url->host.empty()) {
            std::cerr << "gimbal-replay: --video: expected udp://HOST:PORT"
                      << (url ? "" : " (" + url.error().message + ")") << "\n";
            return {std::nullopt, 1};
        }
    }
    if (o.loop && o.hold) {
        std::cerr << "gimbal-replay: --loop and --hold exclude each other\n";
        return {std::nullopt, 1};
    }
    return {o, 0};
}

}  // namespace gimbal_replay
