// Roads and moving objects in the simulated camera's picture (sim/ground_objects.hpp;
// docs/simulator.md "Moving objects"), drawn on the ground texture where the renderer's rays
// meet it - so a hill hides them as it hides the ground. Level 0 roads go under the
// landmarks; objects, the highway's deck (level 1) and what drives on it go over everything,
// in that order, so the deck hides what drives beneath. Each object has its shadow (the sun
// of scene_style.hpp) and parts a tracker can hold on to: a car's windows and roof, a truck's
// cab and box, a boat's cabin and wake. Internal to lib/sim's renderer.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sim/ground_objects.hpp"
#include "sim/scene_colour.hpp"

namespace gimbal::sim {

class SceneObjects {
  public:
    SceneObjects();

    // The objects of the frame about to be drawn.
    void set_objects(std::span<const ObjectState> objects);

    // What may show on the ground within [x0, x1] x [y0, y1] (TerrainXY) widened by margin.
    struct Near {
        std::array<std::uint16_t, 12> segments{};
        std::size_t n_segments = 0;
        std::array<std::uint16_t, 8> bodies{};
        std::size_t n_bodies = 0;
    };
    void near(double x0, double x1, double y0, double y1, double margin, Near& out) const;

    // Level 0 roads over the ground's colour c at (x, y); px_per_m: the pixel footprint.
    Colour roads_below(Colour c, float x, float y, float px_per_m, const Near& near) const;
    // Objects, decks and the objects on them.
    Colour above(Colour c, float x, float y, float px_per_m, const Near& near) const;

  private:
    struct Segment {
        float ax, ay, dx, dy, inv_len2, halfwidth;
        int level;
        float x0, x1, y0, y1;  // bounds, halfwidth included
    };
    struct Body {
        float x, y;
        float fe, fn;  // unit vector of the nose, east and north
        float half_length, half_width;
        float shadow_e, shadow_n;  // where the shadow lies, metres
        float reach;
        ObjectKind kind;
        int level;
        Colour body, roof;
    };
    Colour draw_body(Colour c, const Body& b, float x, float y, float px) const;
    Colour draw_deck(Colour c, const Segment& s, float x, float y, float px) const;

    std::vector<Segment> segments_;
    std::vector<Body> bodies_;
    Colour asphalt_, concrete_, parapet_, glass_, cargo_, cabin_, foam_;
};

}  // namespace gimbal::sim
