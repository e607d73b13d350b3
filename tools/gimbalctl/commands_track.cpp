// Section 20 of the interface contract: visual tracking - `track X Y` (a box of --size around
// the point), `track --box X0 Y0 X1 Y1`, either in pixels with --pixels, and `track-stop`.
// Help groups and descriptions come from the command catalogue.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_table.hpp"
#include "numbers.hpp"
#include "params.hpp"

namespace gimbalctl {
namespace {

// The request's keys renamed to their pixel forms (x -> px, x0 -> px0, ...).
void to_pixels(Json& j) {
    for (const char* key : {"x", "y", "x0", "y0", "x1", "y1"}) {
        if (!j.contains(key)) continue;
        j[std::string("p") + key] = j[key];
        j.erase(key);
    }
}

void add_track(CommandTable& table) {
    Command& command = table.add("track", "track");
    auto p = std::make_shared<Params>(command.app);
    CLI::Option* x = p->number(
        "X", "x", "the object's image position to the right: -1 left edge .. 1 right edge");
    p->number("Y", "y", "the object's image position down: -1 top edge .. 1 bottom edge");
    auto box = std::make_shared<std::vector<std::string>>();
    CLI::Option* box_option =
        command.app
            ->add_option("--box", *box,
                         "the object's box instead of a point: left, top, right, bottom edges "
                         "(JSON \"x0\", \"y0\", \"x1\" and \"y1\")")
            ->expected(4)
            ->check(number_check());
    box_option->type_name("NUMBER");
    p->number("--size", "size", "a point's box side as a fraction of the image width");
    p->flag("--steer,!--no-steer", "steer", "keep the gimbal on the object");
    auto pixels = std::make_shared<bool>(false);
    command.app
        ->add_flag("--pixels", *pixels,
                   "positions are pixels from the image's top-left corner (JSON \"px\", \"py\", "
                   "\"px0\", \"py0\", \"px1\" and \"py1\" instead of \"x\", \"y\", \"x0\", ...)")
        ->default_str("off");
    p->check([x, box_option] {
        const bool point = x->count() > 0;
        if (point == (box_option->count() > 0))
            throw CLI::ValidationError("track", "give X Y or --box X0 Y0 X1 Y1");
    });
    command.params = [p, box, box_option, pixels] {
        Json j = p->json();
        if (box_option->count() > 0) {
            const char* keys[] = {"x0", "y0", "x1", "y1"};
            for (std::size_t i = 0; i < 4 && i < box->size(); ++i)
                j[keys[i]] = number_json((*box)[i]);
        }
        if (*pixels) to_pixels(j);
        return j;
    };
}

}  // namespace

void add_track_commands(CommandTable& table) {
    add_track(table);
    table.add("track-stop", "track_stop");
}

}  // namespace gimbalctl
