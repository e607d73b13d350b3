// Sections 15 and 16 of the interface contract: the commands gimbald answers from the ground
// and the gimbal's image - elevation, locate, point, project. Help groups and descriptions
// come from the command catalogue.
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

// X Y across the image (-1..1, 0 0 the centre), or pixels with --pixels: sent as x,y or
// px,py.
void image_position(Command& command) {
    auto p = std::make_shared<Params>(command.app);
    auto pixels = std::make_shared<bool>(false);
    p->number("X", "x", "image position to the right: -1 left edge .. 1 right edge")->required();
    p->number("Y", "y", "image position down: -1 top edge .. 1 bottom edge")->required();
    command.app
        ->add_flag("--pixels", *pixels,
                   "X and Y are pixels from the image's top-left corner, of the telemetry's "
                   "pixel_width x pixel_height (JSON \"px\" and \"py\" instead of \"x\" and \"y\")")
        ->default_str("off");
    command.params = [p, pixels, previous = command.params] {
        Json j = previous();
        const Json position = p->json();  // named: items() of a temporary dangles
        for (const auto& [key, value] : position.items()) j[key] = value;
        if (*pixels) {
            j["px"] = j["x"];
            j["py"] = j["y"];
            j.erase("x");
            j.erase("y");
        }
        return j;
    };
}

void add_elevation(CommandTable& table) {
    Command& command = table.add("elevation", "elevation");
    auto p = params_of(command);
    p->number("LAT", "lat", "latitude, degrees, north positive")->required();
    p->number("LON", "lon", "longitude, degrees, east positive")->required();
}

void add_locate(CommandTable& table) {
    Command& command = table.add("locate", "locate");
    image_position(command);
}

void add_point(CommandTable& table) {
    Command& command = table.add("point", "point");
    auto p = params_of(command);
    p->flag("--stare", "stare", "stare at the point")->default_str("off");
    image_position(command);
}

void add_project(CommandTable& table) {
    Command& command = table.add("project", "project");
    auto p = params_of(command);
    p->number("LAT", "lat", "latitude, degrees, north positive")->required();
    p->number("LON", "lon", "longitude, degrees, east positive")->required();
    p->number("ALT", "alt", "altitude above the WGS84 ellipsoid, metres")->required();
}

}  // namespace

void add_ground_commands(CommandTable& table) {
    add_elevation(table);
    add_locate(table);
    add_point(table);
    add_project(table);
}

}  // namespace gimbalctl
