// What the simulated camera truly shows of each moving object in a frame (sim/ground_objects):
// where it is on the ground and in the picture, and how much of it can be seen - the truth a
// tracking test compares gimbald's track with (gimbal-sim --objects-log, docs/simulator.md
// "Moving objects"). Image coordinates are the contract's section 16 ones (-1..1, y down),
// computed with the frame's own camera pose. Pure.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "geo/footprint.hpp"
#include "geo/image.hpp"
#include "sim/ground_objects.hpp"

namespace gimbal::sim_video {

struct ImageBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct ObjectTruth {
    sim::ObjectState state;
    double slant_range_m = 0;           // from the camera
    std::optional<geo::ImagePoint> at;  // its centre, when in front of the camera
    std::optional<ImageBox> box;        // its outline's bounds, when all of it is in front
    bool in_picture = false;            // the centre within -1..1
    // Of points spread over its body: those in the picture, not under a deck, and not behind
    // the terrain (seen from the camera).
    double visible_fraction = 0;
    enum class Hidden { no, deck, terrain } hidden = Hidden::no;  // why the centre is not seen
};

std::vector<ObjectTruth> object_truth(const geo::CameraPose& camera,
                                      std::span<const sim::ObjectState> objects);

}  // namespace gimbal::sim_video
