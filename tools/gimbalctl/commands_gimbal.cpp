// The gimbal commands of the command catalogue (lib/command/catalogue.hpp): their arguments
// on the command line. The help group (which protocols plan them) and the one-line description
// come from the catalogue and the protocol registry. Units are the contract's: degrees,
// metres, seconds or milliseconds as the key says. Ranges are checked by the daemon, which
// answers out_of_range naming the key; gimbalctl only checks types and closed name lists.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_table.hpp"
#include "numbers.hpp"
#include "params.hpp"

namespace gimbalctl {
namespace {

std::shared_ptr<Params> params_of(Command& command) {
    auto params = std::make_shared<Params>(command.app);
    command.params = [params] { return params->json(); };
    return params;
}

void add_geopoint(CommandTable& table) {
    Command& command = table.add("geopoint", "geopoint");
    auto p = params_of(command);
    p->number("LAT", "lat", "latitude, degrees, north positive")->required();
    p->number("LON", "lon", "longitude, degrees, east positive")->required();
    p->number("ALT", "alt",
              "altitude, metres (reference: --alt-ref); left out: the daemon's terrain gives "
              "the ground's height there")
        ->default_str("the terrain's");
    p->text("--alt-ref", "alt_ref",
            "altitude reference: wgs84 (ellipsoid), msl (converted by the daemon with the "
            "latest telemetry's geoid undulation) or terrain (ALT is height above the ground)")
        ->check(CLI::IsMember({"wgs84", "msl", "terrain"}))
        ->type_name("REF")
        ->default_str("wgs84");
    p->numbers("--vel-ned", "vel_ned", 3, "target velocity north, east, down, m/s")
        ->type_name("N E D")
        ->default_str("0 0 0");
    p->number("--joystick-range", "joystick_range_m", "joystick range, metres (0..65535)")
        ->type_name("M")
        ->default_str("0");
    p->flag("--stare", "stare", "stare at the point")->default_str("off");
    p->flag("--closure", "closure", "closure flag")->default_str("off");
}

void add_path(CommandTable& table) {
    Command& command = table.add("path", "path");
    auto p = params_of(command);
    auto points = std::make_shared<std::vector<std::string>>();
    CLI::Option* points_option =
        command.app
            ->add_option("POINT", *points,
                         "1..15 path points LAT,LON,ALT (degrees, degrees, "
                         "metres above WGS84; --alt-ref terrain: above the ground); LAT,LON "
                         "takes the ground's height from the daemon's terrain")
            ->check(point_check());
    p->custom("points", points_option, [points] {
        Json array = Json::array();
        for (const std::string& point : *points) array.push_back(*parse_point(point));
        return array;
    });
    CLI::Option* down = p->flag("--down", "down", "point straight down (no points)");
    down->excludes(points_option)->default_str("off");
    p->text("--alt-ref", "alt_ref", "altitude reference of the points: wgs84 or terrain")
        ->check(CLI::IsMember({"wgs84", "terrain"}))
        ->type_name("REF")
        ->default_str("wgs84");
    p->number("--along-step", "along_step_deg", "along-track step, degrees (0..180)")
        ->type_name("DEG")
        ->default_str("0");
    p->integer("--cross-steps", "cross_steps", "cross-track steps (0..15)")
        ->type_name("N")
        ->default_str("0");
    p->number("--cross-ratio", "cross_ratio", "cross-track step ratio (0..2.55)")
        ->type_name("R")
        ->default_str("0");
    p->check([points_option, down] {
        if (points_option->count() == 0 && down->count() == 0) {
            throw CLI::ValidationError("path", "give path points LAT,LON[,ALT] or --down");
        }
    });
}

void add_laser(CommandTable& table) {
    Command& command =
        table.add("laser", "laser", "enable, arm and fire are always sent: false unless given.");
    auto p = params_of(command);
    p->integer("--index", "index", "laser index (0..1)")->type_name("I")->default_str("0");
    p->flag("--enable", "enable", "enable the laser", true)->default_str("off (sent as false)");
    p->flag("--arm", "arm", "arm the laser", true)->default_str("off (sent as false)");
    p->flag("--fire", "fire", "fire (needs --enable --arm and laser.allow_fire)", true)
        ->default_str("off (sent as false)");
    p->integer("--on-ms", "on_ms", "on time, ms (0..65535)")->type_name("MS")->default_str("0");
    p->integer("--off-ms", "off_ms", "off time, ms (0..65535)")->type_name("MS")->default_str("0");
    p->integer("--prf-code", "prf_code", "PRF code (0..65535)")->type_name("N")->default_str("0");
    p->text("--password", "password", "laser password, 0..15 ASCII characters")
        ->type_name("TEXT")
        ->default_str("\"\"");
    p->flag("--safety-bypass", "safety_bypass",
            "bypass the gimbal's laser safety (needs laser.allow_safety_bypass)")
        ->default_str("off");
}

void add_pan_tilt(CommandTable& table, const std::string& name, const std::string& unit,
                  const std::string& stabilized_default) {
    Command& command = table.add(name, name);
    auto p = params_of(command);
    p->number("PAN", "pan", "pan, " + unit)->required();
    p->number("TILT", "tilt", "tilt, " + unit)->required();
    p->flag("--stabilized,!--no-stabilized", "stabilized", "inertial stabilization on or off")
        ->default_str(stabilized_default);
    p->number("--impulse-time", "impulse_time_s", "impulse time, seconds (0..25.5)")
        ->type_name("S")
        ->default_str("0");
}

void add_mode(CommandTable& table) {
    Command& command = table.add("mode", "mode");
    auto p = params_of(command);
    p->text("NAME", "mode", "the mode")
        ->required()
        ->check(CLI::IsMember(
            {"disabled", "ffc_auto", "ffc_manual", "calibration", "scene", "track", "geo_rate"}));
}

void add_stare_ack(CommandTable& table) {
    Command& command = table.add("stare-ack", "stare_ack");
    auto p = params_of(command);
    p->integer("--system-time", "system_time_ms", "system time of the StareStart, ms")
        ->type_name("MS")
        ->default_str("the latest StareStart's");
}

void add_retract(CommandTable& table) {
    Command& command = table.add("retract", "retract");
    auto p = params_of(command);
    p->text("ACTION", "action", "deploy, retract or disable")
        ->required()
        ->check(CLI::IsMember({"deploy", "retract", "disable"}));
}

void add_camera_switch(CommandTable& table) {
    Command& command = table.add("camera-switch", "camera_switch");
    auto p = params_of(command);
    p->integer("INDEX", "index", "camera index")->required();
}

void add_camera_zoom(CommandTable& table) {
    Command& command = table.add("camera-zoom", "camera_zoom");
    auto p = params_of(command);
    p->number("ZOOM", "zoom", "zoom ratio")->required();
    p->number("--focus", "focus", "focus (-1: leave as it is)")->type_name("F")->default_str("-1");
    p->integer("--index", "index", "camera index")->type_name("I")->default_str("0");
}

void add_range(CommandTable& table) {
    Command& command = table.add("range", "range");
    auto p = params_of(command);
    p->number("RANGE_M", "range_m", "range, metres")->required();
    p->integer("--max-age-ms", "max_age_ms", "how long the range stays valid, ms")
        ->type_name("MS")
        ->default_str("daemon's");
    p->text("--source", "source", "range source name, e.g. laser")
        ->type_name("NAME")
        ->default_str("daemon's");
}

void add_request(CommandTable& table) {
    Command& command = table.add("request", "request");
    auto p = params_of(command);
    p->text("PACKET", "packet",
            "packet name (crown_version, cameras, limits, network_settings, ...) or "
            "versions")
        ->required();
}

// A flag pair "--x/--no-x" that must be given one way or the other.
void required_switch(Params& p, const std::string& name, const std::string& description) {
    p.flag("--" + name + ",!--no-" + name, name, description)
        ->required()
        ->default_str("none: one of the two is required");
}

void add_output(CommandTable& table) {
    Command& command = table.add("viewpro-output", "viewpro_output");
    auto p = params_of(command);
    p->text("--osd", "osd", "target or uav")
        ->required()
        ->check(CLI::IsMember({"target", "uav"}))
        ->type_name("WHAT")
        ->default_str("none: required");
    required_switch(*p, "serial", "output on the serial port, or not");
    required_switch(*p, "network", "output on the network, or not");
    p->text("--format", "format", "out1, out2, out3 or out4")
        ->required()
        ->check(CLI::IsMember({"out1", "out2", "out3", "out4"}))
        ->type_name("FMT")
        ->default_str("none: required");
}

void add_adjust(CommandTable& table) {
    Command& command = table.add("viewpro-adjust", "viewpro_adjust");
    auto p = params_of(command);
    CLI::Option* yaw = p->number("--yaw", "yaw_deg", "yaw trim, degrees (-20..20, step 0.01)")
                           ->type_name("DEG")
                           ->default_str("not sent");
    CLI::Option* pitch =
        p->number("--pitch", "pitch_deg", "pitch trim, degrees (-20..20, step 0.01)")
            ->type_name("DEG")
            ->default_str("not sent");
    p->check([yaw, pitch] {
        if (yaw->count() == 0 && pitch->count() == 0) {
            throw CLI::ValidationError("viewpro-adjust", "give --yaw and/or --pitch");
        }
    });
}

void add_vehicle(CommandTable& table) {
    Command& command = table.add("vehicle", "vehicle");
    auto p = params_of(command);
    const auto required_number = [&p](const std::string& name, const std::string& key,
                                      const std::string& type, const std::string& description) {
        p->number(name, key, description)
            ->required()
            ->type_name(type)
            ->default_str("none: required");
    };
    required_number("--roll", "roll", "DEG", "vehicle roll, degrees");
    required_number("--pitch", "pitch", "DEG", "vehicle pitch, degrees");
    required_number("--yaw", "yaw", "DEG", "vehicle yaw, degrees");
    required_number("--lat", "lat", "DEG", "latitude, degrees");
    required_number("--lon", "lon", "DEG", "longitude, degrees");
    required_number("--alt-msl", "alt_msl", "M", "altitude above mean sea level, metres");
    p->numbers("--vel-ned", "vel_ned", 3, "velocity north, east, down, m/s (selects IN2)")
        ->type_name("N E D")
        ->default_str("not sent (IN1)");
    p->text("--time", "time", "UTC time, ISO-8601, e.g. 2026-11-21T06:41:50.123Z")
        ->type_name("ISO")
        ->default_str("now");
}

}  // namespace

void add_gimbal_commands(CommandTable& table) {
    add_geopoint(table);
    add_path(table);
    add_laser(table);
    add_pan_tilt(table, "position", "degrees", "off");
    add_pan_tilt(table, "rate", "degrees/s", "on");
    table.add("center", "center");  // no parameters: group and summary from the catalogue
    add_mode(table);
    add_stare_ack(table);
    add_retract(table);
    add_camera_switch(table);
    add_camera_zoom(table);
    add_range(table);
    add_request(table);
    add_output(table);
    add_adjust(table);
    add_vehicle(table);
}

}  // namespace gimbalctl
