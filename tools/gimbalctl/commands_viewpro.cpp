// Section 4.3 of the interface contract: Viewpro commands.
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "command_table.hpp"
#include "params.hpp"

namespace gimbalctl {
namespace {

std::shared_ptr<Params> params_of(Command& command) {
    auto params = std::make_shared<Params>(command.app);
    command.params = [params] { return params->json(); };
    return params;
}

// A flag pair "--x/--no-x" that must be given one way or the other.
void required_switch(Params& p, const std::string& name, const std::string& description) {
    p.flag("--" + name + ",!--no-" + name, name, description)
        ->required()
        ->default_str("none: one of the two is required");
}

void add_output(CommandTable& table) {
    Command& command = table.add("viewpro-output", "viewpro_output", group_viewpro,
                                 "Set what the gimbal reports and where (mode frame AA 55 0F).");
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
    Command& command = table.add("viewpro-adjust", "viewpro_adjust", group_viewpro,
                                 "Trim yaw and/or pitch (frames AA 55 06 / AA 55 36).");
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
    Command& command = table.add("vehicle", "vehicle", group_viewpro,
                                 "Send the vehicle's attitude and position (IN1, or IN2 with "
                                 "--vel-ned).");
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

void add_viewpro_commands(CommandTable& table) {
    add_output(table);
    add_adjust(table);
    add_vehicle(table);
}

}  // namespace gimbalctl
