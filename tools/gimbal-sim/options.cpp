#include "options.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <map>
#include <vector>

namespace gimbal_sim {

namespace {

namespace protocols = gimbal::protocols;

// NAME, SYNOPSIS and DESCRIPTION: the protocols and what each model does come from the
// registry (Simulator::manual).
std::string description() {
    std::string names;
    std::string displays;
    std::string models;
    for (const auto* p : protocols::entries()) {
        names += (names.empty() ? "" : "|") + std::string(p->name);
        displays += (displays.empty() ? "" : ", ") + std::string(p->display_name);
        models += "\n" + std::string(p->simulator.manual);
    }
    return "NAME\n"
           "       gimbal-sim - simulated gimbals (" +
           displays +
           ") for tests, demos\n"
           "       and training\n"
           "\n"
           "SYNOPSIS\n"
           "       gimbal-sim [--protocol " +
           names +
           "] [--port N] [--pty [--pty-link PATH]] [--udp PORT]\n"
           "                  [--no-tcp] [fault options] [gimbal options]\n"
           "\n"
           "DESCRIPTION\n"
           "       Serves a simulated gimbal of --protocol (default " +
           std::string(protocols::entries().front()->name) +
           ") over TCP (one\n"
           "       client at a time; a new client replaces the old one) and/or a\n"
           "       pseudo-terminal. The model keeps running between connections. See\n"
           "       docs/simulator.md.\n" +
           models;
}

constexpr const char* footer_start = R"(OUTPUT
       On standard output, one line per endpoint as soon as it is ready, then
       nothing else:
           tcp: 127.0.0.1:8747
           pty: /dev/pts/5
           discovery: 0.0.0.0:8745
       Diagnostics (clients connecting, faults) go to standard error.

DISCOVERY
       For a protocol with a broadcast discovery (see docs/simulator.md), a
       discovery request arriving on UDP --discovery-port is answered with the
       gimbal's reply, sent to the requester's address at --discovery-reply-port
       and, when different, to the request's source port.

TERRAIN
       The simulator's ground is an analytic terrain around 45.7 N 121.5 W: a
       plateau near 400 m, hills up to about 1000 m and a river valley (heights
       above the WGS84 ellipsoid); the models that range on it say so above.
       --write-dem FILE writes it as a Float32 GeoTIFF (1 arc-second, 45.5..45.9 N,
       121.8..121.2 W) and exits: give that file to gimbald's terrain section with
       "geoid": "none", and gimbald's ground agrees with the simulated gimbal's
       target.

RX LOG
       --rx-log FILE writes one JSON object per line for every valid frame
       received from the controller, flushed at once; t is seconds since
       gimbal-sim started, src "tcp", "pty" or "udp".
)";

constexpr const char* footer_end = R"(
FAULT INJECTION
       --drop-after S closes each TCP client S seconds after it connected.
       --corrupt-fraction F sends that fraction of frames with a wrong checksum.
       --junk-every N inserts a stray sync byte and noise after every N frames.
       --stall-after S --stall-for D: S seconds after a TCP client connects (or
       after start, for the pty) the gimbal goes silent for D seconds; it still
       hears commands meanwhile.
       --stall-reading-after S --stall-reading-for D: S seconds after a TCP client
       connects (or the pty is opened) the gimbal stops reading for D seconds; it
       still talks. Its input buffers fill and the controller's writes block.
       --read-baud B: read no faster than a serial line at B baud drains (10 bits
       a byte), on TCP and the pty alike.
       With either read fault the TCP receive buffer is 4 KiB, so backpressure
       reaches the controller at once.

EXIT STATUS
       0 stopped by SIGINT or SIGTERM (or --help); 1 bad command line; 2 runtime
       failure (a port cannot be bound, no pty).

EXAMPLES
       gimbal-sim --port 0 --no-discovery
       gimbal-sim --write-dem build/release/sim-dem.tif
       gimbal-sim --no-tcp --pty --pty-link /tmp/gimbal
       gimbal-sim --corrupt-fraction 0.05 --junk-every 20 --rx-log rx.jsonl
       gimbal-sim --protocol viewpro --no-tcp --pty --pty-link /tmp/viewpro
)";

double unix_time_now_s() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

std::string footer() {
    std::string rx;
    for (const auto* p : protocols::entries()) rx += std::string(p->simulator.rx_log_manual);
    return std::string(footer_start) + rx + video_manual() + footer_end;
}

// The value of a protocol's flag as parsed (stored per flag name; several protocols may
// declare the same flag).
struct FlagValue {
    const protocols::SimFlag* flag = nullptr;
    CLI::Option* option = nullptr;
    double number = 0;
    std::int64_t integer = 0;
    std::string text;
    bool set = false;
};

CLI::Option* add_flag(CLI::App& app, const protocols::SimFlag& f, const nlohmann::json& defaults,
                      FlagValue& v, const std::string& group) {
    using Type = protocols::SimFlag::Type;
    using Check = protocols::SimFlag::Check;
    const std::string name(f.name);
    const std::string help(f.help);
    CLI::Option* o = nullptr;
    switch (f.type) {
        case Type::number:
            o = app.add_option(name, v.number, help);
            break;
        case Type::integer:
            o = app.add_option(name, v.integer, help);
            break;
        case Type::text:
            o = app.add_option(name, v.text, help);
            break;
        case Type::flag:
            o = app.add_flag(name, v.set, help);
            break;
    }
    o->group(group);
    const auto d = defaults.find(std::string(f.key));
    if (f.type != Type::flag && d != defaults.end())
        o->default_str(d->is_string() ? d->get<std::string>() : d->dump());
    switch (f.check) {
        case Check::none:
            break;
        case Check::range:
            if (f.type == Type::text)
                o->check(CLI::Validator(
                    [max = f.max](std::string& s) {
                        return static_cast<double>(s.size()) <= max
                                   ? std::string()
                                   : "at most " + std::to_string(static_cast<int>(max)) +
                                         " characters";
                    },
                    "AT MOST " + std::to_string(static_cast<int>(f.max)) + " CHARACTERS"));
            else
                o->check(CLI::Range(f.min, f.max));
            break;
        case Check::non_negative:
            o->check(CLI::NonNegativeNumber);
            break;
        case Check::positive:
            o->check(CLI::PositiveNumber);
            break;
    }
    return o;
}

nlohmann::json flag_json(const FlagValue& v) {
    using Type = protocols::SimFlag::Type;
    switch (v.flag->type) {
        case Type::number:
            return v.number;
        case Type::integer:
            return v.integer;
        case Type::text:
            return v.text;
        case Type::flag:
            return true;
    }
    return nullptr;
}

}  // namespace

ParsedOptions parse_options(int argc, char** argv) {
    ToolOptions o;
    o.protocol = std::string(protocols::entries().front()->name);
    auto& scenario = o.scenario;
    scenario.unix_time_s = unix_time_now_s();
    double lat = 0, lon = 0, alt = 0, terrain_alt = 0, geoid = 0;
    bool no_tcp = false;
    bool no_discovery = false;
    bool version = false;

    CLI::App app{description(), "gimbal-sim"};
    app.footer(footer());
    app.get_formatter()->column_width(34);

    std::vector<std::string> names = protocols::names();
    app.add_option("--protocol", o.protocol, "Gimbal protocol to simulate")
        ->check(CLI::IsMember(names))
        ->capture_default_str();
    app.add_option("--bind", o.bind, "Address the TCP server listens on")->capture_default_str();
    app.add_option("--port", o.port, "TCP port; 0 picks a free one (printed)")
        ->capture_default_str();
    app.add_flag("--no-tcp", no_tcp, "Do not serve TCP");
    app.add_option("--udp", o.udp_port,
                   "Also serve UDP on --bind:PORT (0: a free one, printed); replies go to the "
                   "latest sender");
    app.add_flag("--pty", o.pty, "Serve a pseudo-terminal; prints its device path");
    app.add_option("--pty-link", o.pty_link, "Also make a symlink at PATH to the pty device");
    app.add_option("--discovery-port", o.discovery_port,
                   "UDP port for discovery requests; 0 picks a free one (printed)")
        ->capture_default_str();
    app.add_option("--discovery-reply-port", o.discovery_reply_port,
                   "UDP port discovery replies go to; 0 = the request's source port")
        ->capture_default_str();
    app.add_flag("--no-discovery", no_discovery,
                 "Do not answer discovery requests (always so for a protocol without)");

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
    app.add_option("--stall-reading-after", o.stall_reading_after_s,
                   "Stop reading S seconds after a client connects")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--stall-reading-for", o.stall_reading_for_s,
                   "How long the gimbal does not read, seconds")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--read-baud", o.read_baud, "Read no faster than a serial line at B baud")
        ->check(CLI::Range(300u, 4000000u));
    app.add_option("--seed", scenario.seed, "Seed of sensor noise and faults")
        ->capture_default_str();
    app.add_option("--rx-log", o.rx_log, "Write every packet received as a JSON line to FILE");
    app.add_option("--write-dem", o.write_dem,
                   "Write the simulator's terrain as a GeoTIFF DEM to FILE and exit")
        ->type_name("FILE");

    // Settings every model takes; each keeps its own default when one is not given.
    auto* lat_option = app.add_option("--lat", lat, "Aircraft (circle centre) latitude, degrees")
                           ->check(CLI::Range(-89.0, 89.0))
                           ->default_str("the model's");
    auto* lon_option = app.add_option("--lon", lon, "Aircraft (circle centre) longitude, degrees")
                           ->check(CLI::Range(-180.0, 180.0))
                           ->default_str("the model's");
    auto* alt_option =
        app.add_option("--alt", alt, "Flight altitude, metres (the model says above what)")
            ->default_str("the model's");
    auto* terrain_option =
        app.add_option("--terrain-alt", terrain_alt,
                       "Flat ground at this height instead of the terrain, metres (the model "
                       "says above what)")
            ->default_str("the model's");
    auto* geoid_option =
        app.add_option("--geoid-undulation", geoid, "Geoid height above the ellipsoid, metres")
            ->default_str("the model's");

    // Each protocol's own flags, from its registry entry, grouped by protocol. A flag two
    // protocols share is declared once and reaches whichever is chosen.
    std::map<std::string, FlagValue, std::less<>> values;
    for (const auto* p : protocols::entries()) {
        const auto defaults = p->simulator.defaults ? p->simulator.defaults() : nlohmann::json();
        const std::string group =
            std::string(p->display_name) + " gimbal (--protocol " + std::string(p->name) + ")";
        for (const auto& f : p->simulator.flags) {
            auto [it, added] = values.try_emplace(std::string(f.name));
            if (!added) continue;
            it->second.flag = &f;
            it->second.option = add_flag(app, f, defaults, it->second, group);
        }
    }
    add_video_options(app, o.video);
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
    // Discovery is the protocol's own (a vendor SDK's broadcast); others have none.
    o.discovery = !no_discovery && o.entry().simulator.is_discovery_request != nullptr;
    if (lat_option->count() > 0) scenario.lat_deg = lat;
    if (lon_option->count() > 0) scenario.lon_deg = lon;
    if (alt_option->count() > 0) scenario.alt_m = alt;
    if (terrain_option->count() > 0) scenario.terrain_alt_m = terrain_alt;
    if (geoid_option->count() > 0) scenario.geoid_undulation_m = geoid;
    for (const auto& f : o.entry().simulator.flags) {
        const auto& v = values.at(std::string(f.name));
        if (v.option->count() > 0) scenario.options[std::string(f.key)] = flag_json(v);
    }
    if (!o.write_dem.empty()) return {o, 0};  // serves nothing
    if (!o.tcp && !o.pty && !o.udp_port) {
        std::cerr << "gimbal-sim: nothing to serve: --no-tcp needs --pty or --udp\n";
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
    if (o.stall_reading_after_s > 0 && o.stall_reading_for_s <= 0) {
        std::cerr << "gimbal-sim: --stall-reading-after needs --stall-reading-for\n";
        return {std::nullopt, 1};
    }
    if (o.video.url.empty() && !o.video.objects_log.empty()) {
        std::cerr << "gimbal-sim: --objects-log needs --video (the objects are in the picture)\n";
        return {std::nullopt, 1};
    }
    if (std::string error;
        !o.video.url.empty() && !video_sender_options(o.video, o.entry(), error)) {
        std::cerr << "gimbal-sim: " << error << "\n";
        return {std::nullopt, 1};
    }
    return {o, 0};
}

}  // namespace gimbal_sim
