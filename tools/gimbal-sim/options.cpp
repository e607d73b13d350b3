#include "options.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>

namespace gimbal_sim {

namespace {

constexpr const char* description = R"(NAME
       gimbal-sim - simulated Trillium Orion and Viewpro gimbals for tests, demos
       and training

SYNOPSIS
       gimbal-sim [--protocol orion|viewpro] [--port N] [--pty [--pty-link PATH]]
                  [--no-tcp] [fault options] [gimbal options]

DESCRIPTION
       Serves a simulated Orion gimbal speaking the OrionPublic protocol over TCP (one
       client at a time; a new client replaces the old one) and/or a pseudo-terminal.
       The gimbal rides on an aircraft flying a level circle, sends GeolocateTelemetry
       at 10 Hz, Performance at 4 Hz, InsQuality, GpsData, SoftwareDiagnostics,
       LaserStates and RetractStatus at 1 Hz, Diagnostics every 3 s and Vibration
       every 5 s, and obeys OrionCmd (echoed back), GeopointCmd, OrionPath with
       step-stare, laser, retract, camera and configuration packets. Zero-length
       packets are requests for that packet. The model keeps running between
       connections. See docs/simulator.md.

       --protocol viewpro serves a simulated Viewpro gimbal speaking the target
       GPS-coordinates protocol instead (usually over --pty, as its serial port;
       TCP works the same way; no discovery). It is silent until a mode command
       (AA 55 0F MM FF) enables serial output, then sends the selected OUT1..OUT4
       frame at 10 Hz. IN1/IN2/IN3 frames set the vehicle position and attitude,
       AA 55 06/36 XX FF shift the calculated point; the target is where the line
       of sight meets flat terrain at --terrain-alt (MSL), or the IN3 laser
       distance along it.
)";

constexpr const char* footer = R"(OUTPUT
       On standard output, one line per endpoint as soon as it is ready, then
       nothing else:
           tcp: 127.0.0.1:8747
           pty: /dev/pts/5
           discovery: 0.0.0.0:8745
       Diagnostics (clients connecting, faults) go to standard error.

DISCOVERY
       A zero-length CROWN_VERSION request (D0 0D 28 00 0B CA) arriving on UDP
       --discovery-port is answered with the CrownVersion packet, sent to the
       requester's address at --discovery-reply-port and, when different, to the
       request's source port.

RX LOG
       --rx-log FILE writes one JSON object per line for every checksum-valid
       packet received from the controller, flushed at once:
           {"t": 1.234, "src": "tcp", "id": 213, "name": "geopoint_cmd", "len": 21,
            "hex": "d00dd515...", "packet": {...}}
       t is seconds since gimbal-sim started, hex the whole frame as received
       (sync bytes to checksum), packet the decoded packet (absent when it does not
       decode, e.g. a zero-length request). With --protocol viewpro, one line per
       valid IN frame or AA 55 command:
           {"t": 1.234, "src": "pty", "kind": "in2", "len": 40, "hex": "f9fc...",
            "frame": {...}}
       kind is mode, yaw_shift, pitch_shift, in1, in2 or in3; frame the decoded
       content in JSON units (degrees, metres).

FAULT INJECTION
       --drop-after S closes each TCP client S seconds after it connected.
       --corrupt-fraction F sends that fraction of frames with a wrong checksum.
       --junk-every N inserts a stray sync byte and noise after every N frames.
       --stall-after S --stall-for D: S seconds after a TCP client connects (or
       after start, for the pty) the gimbal goes silent for D seconds; it still
       hears commands meanwhile.

EXIT STATUS
       0 stopped by SIGINT or SIGTERM (or --help); 1 bad command line; 2 runtime
       failure (a port cannot be bound, no pty).

EXAMPLES
       gimbal-sim --port 0 --no-discovery
       gimbal-sim --no-tcp --pty --pty-link /tmp/orion
       gimbal-sim --corrupt-fraction 0.05 --junk-every 20 --rx-log rx.jsonl
       gimbal-sim --protocol viewpro --no-tcp --pty --pty-link /tmp/viewpro
)";

double unix_time_now_s() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

double gps_time_now_s() {
    return gimbal::sim::gps_time_from_unix_s(unix_time_now_s());
}

// The options both models understand, taken from the command line only when given there:
// each model keeps its own defaults otherwise.
void apply_to_viewpro(const CLI::App& app, const gimbal::sim::OrionSimOptions& m,
                      gimbal::sim::ViewproSimOptions& v) {
    if (app.count("--lat") > 0) v.lat_deg = m.lat_deg;
    if (app.count("--lon") > 0) v.lon_deg = m.lon_deg;
    if (app.count("--alt") > 0) v.alt_msl_m = m.alt_m;
    if (app.count("--terrain-alt") > 0) v.terrain_alt_msl_m = m.terrain_alt_m;
    if (app.count("--geoid-undulation") > 0) v.geoid_undulation_m = m.geoid_undulation_m;
    v.seed = m.seed;
}

}  // namespace

ParsedOptions parse_options(int argc, char** argv) {
    ToolOptions o;
    auto& m = o.model;
    auto& v = o.viewpro_model;
    m.gps_time_at_start_s = gps_time_now_s();
    v.unix_time_at_start_s = unix_time_now_s();
    bool no_laser = false;
    bool no_tcp = false;
    bool no_discovery = false;
    bool no_retract = false;
    bool counter_clockwise = false;
    bool version = false;

    CLI::App app{description, "gimbal-sim"};
    app.footer(footer);
    app.get_formatter()->column_width(34);

    app.add_option("--protocol", o.protocol, "Gimbal protocol to simulate")
        ->check(CLI::IsMember({"orion", "viewpro"}))
        ->capture_default_str();
    app.add_option("--bind", o.bind, "Address the TCP server listens on")->capture_default_str();
    app.add_option("--port", o.port, "TCP port; 0 picks a free one (printed)")
        ->capture_default_str();
    app.add_flag("--no-tcp", no_tcp, "Do not serve TCP");
    app.add_flag("--pty", o.pty, "Serve a pseudo-terminal; prints its device path");
    app.add_option("--pty-link", o.pty_link, "Also make a symlink at PATH to the pty device");
    app.add_option("--discovery-port", o.discovery_port,
                   "UDP port for discovery requests; 0 picks a free one (printed)")
        ->capture_default_str();
    app.add_option("--discovery-reply-port", o.discovery_reply_port,
                   "UDP port discovery replies go to; 0 = the request's source port")
        ->capture_default_str();
    app.add_flag("--no-discovery", no_discovery,
                 "Do not answer discovery requests (always so for viewpro)");

    app.add_option("--drop-after", o.drop_after_s, "Close each TCP client after S seconds")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--corrupt-fraction", o.corrupt_fraction,
                   "Fraction (0..1) of frames sent with a wrong checksum")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--junk-every", o.junk_every, "Insert junk bytes after every N frames");
    app.add_option("--stall-after", o.stall_after_s, "Go silent S seconds after a client connects")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--stall-for", o.stall_for_s, "How long the silence lasts, seconds")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--seed", m.seed, "Seed of sensor noise and faults")->capture_default_str();
    app.add_option("--rx-log", o.rx_log, "Write every packet received as a JSON line to FILE");

    // The defaults shown are the Orion's; the Viewpro's differ (docs/simulator.md).
    app.add_option("--lat", m.lat_deg,
                   "Orion: circle centre latitude, degrees. Viewpro: the vehicle's latitude "
                   "before any IN frame (default 6.9428789, the ICD's OUT1 example)")
        ->check(CLI::Range(-89.0, 89.0))
        ->capture_default_str();
    app.add_option("--lon", m.lon_deg,
                   "Orion: circle centre longitude, degrees. Viewpro: the vehicle's longitude "
                   "before any IN frame (default 79.8812446)")
        ->check(CLI::Range(-180.0, 180.0))
        ->capture_default_str();
    app.add_option("--alt", m.alt_m,
                   "Orion: flight altitude above the WGS84 ellipsoid, metres. Viewpro: the "
                   "vehicle's altitude above mean sea level (default 300)")
        ->capture_default_str();
    app.add_option("--radius", m.radius_m, "Circle radius, metres; 0 hovers")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--speed", m.speed_mps, "Ground speed, m/s")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_flag("--counter-clockwise", counter_clockwise, "Circle counter-clockwise");
    app.add_option("--terrain-alt", m.terrain_alt_m,
                   "Orion: height of the flat terrain above the ellipsoid, metres. Viewpro: "
                   "above mean sea level (default 0)")
        ->capture_default_str();
    app.add_option("--geoid-undulation", m.geoid_undulation_m,
                   "Reported geoid height above the ellipsoid, metres (Viewpro: default 0)")
        ->capture_default_str();
    app.add_option("--pan-rate", m.pan_rate_max_dps, "Pan slew rate limit, deg/s")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--tilt-rate", m.tilt_rate_max_dps, "Tilt slew rate limit, deg/s")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--stare-time", m.stare_time_s, "Step-stare stare time, seconds (<= 2.55)")
        ->check(CLI::Range(0.0, 2.55))
        ->capture_default_str();
    app.add_option("--path-speed", m.path_scan_speed_mps,
                   "Path sweep speed without step-stare, m/s")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--laser-password", m.laser_password,
                   "Password the lasers require (default: none)");
    app.add_flag("--no-retract", no_retract, "No retract mechanism installed");

    auto* viewpro = "Viewpro gimbal (--protocol viewpro)";
    app.add_option("--heading", v.yaw_deg, "Vehicle heading before any IN frame, degrees")
        ->group(viewpro)
        ->capture_default_str();
    app.add_option("--gimbal-pitch", v.gimbal_pitch_deg,
                   "Gimbal pitch relative to the vehicle, degrees, up positive")
        ->group(viewpro)
        ->check(CLI::Range(-180.0, 180.0))
        ->capture_default_str();
    app.add_option("--gimbal-yaw", v.gimbal_yaw_deg,
                   "Gimbal yaw relative to the heading, degrees, right positive")
        ->group(viewpro)
        ->check(CLI::Range(-180.0, 180.0))
        ->capture_default_str();
    app.add_option("--gimbal-yaw-rate", v.gimbal_yaw_rate_dps, "Gimbal yaw sweep rate, deg/s")
        ->group(viewpro)
        ->capture_default_str();
    app.add_option("--angle-noise", v.angle_noise_deg,
                   "Noise (1 sigma) on the reported gimbal angles, degrees")
        ->group(viewpro)
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--zoom", v.zoom_position, "Zoom position value reported")
        ->group(viewpro)
        ->capture_default_str();
    app.add_flag("--no-laser", no_laser, "No laser range finder: the LRF field stays 0")
        ->group(viewpro);
    app.add_flag("--version", version, "Print the version and exit");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return {std::nullopt, app.exit(e) == 0 ? 0 : 1};
    }
    if (version) {
        std::cout << "gimbal-sim " << GIMBALD_VERSION << "\n";
        return {std::nullopt, 0};
    }
    o.tcp = !no_tcp;
    o.discovery = !no_discovery;
    m.retract_installed = !no_retract;
    m.clockwise = !counter_clockwise;
    v.has_laser = !no_laser;
    if (o.protocol == "viewpro") {
        o.discovery = false;  // the Orion SDK's broadcast discovery has no Viewpro form
        apply_to_viewpro(app, m, v);
    }
    if (!o.tcp && !o.pty) {
        std::cerr << "gimbal-sim: nothing to serve: --no-tcp needs --pty\n";
        return {std::nullopt, 1};
    }
    if (!o.pty_link.empty() && !o.pty) {
        std::cerr << "gimbal-sim: --pty-link needs --pty\n";
        return {std::nullopt, 1};
    }
    if (o.stall_after_s > 0 && o.stall_for_s <= 0) {
        std::cerr << "gimbal-sim: --stall-after needs --stall-for\n";
        return {std::nullopt, 1};
    }
    if (m.laser_password.size() > 15) {
        std::cerr << "gimbal-sim: --laser-password: at most 15 characters\n";
        return {std::nullopt, 1};
    }
    return {o, 0};
}

}  // namespace gimbal_sim
