// Roads and moving objects in the simulated camera's picture (sim/scene_objects.hpp): a car
// drawn where geo::project puts it, with its shadow on the road; a car under the highway's
// deck not drawn at all; the still scene unchanged where no object is.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "scene_test_support.hpp"
#include "sim/ground_objects.hpp"
#include "sim/scene_renderer.hpp"

using namespace scene_test;

namespace {

sim::I420Frame render(const geo::CameraPose& camera, const std::vector<sim::ObjectState>& objects) {
    sim::SceneRenderer renderer;
    sim::I420Frame frame;
    REQUIRE(renderer.render(camera, frame, objects));
    return frame;
}

// A point `u` metres along the object's nose and `v` to its right, on the ground.
geo::Lla beside(const sim::ObjectState& o, double u, double v) {
    const double h = o.heading_deg * geo::deg2rad;
    const sim::TerrainXY p{o.xy.east_m + u * std::sin(h) + v * std::cos(h),
                           o.xy.north_m + u * std::cos(h) - v * std::sin(h)};
    const geo::LatLon ll = sim::terrain_lat_lon(p);
    return {ll.lat_deg, ll.lon_deg, sim::terrain_height_xy(p)};
}

// The circling Orion's place: above the circle's centre at 1500 m.
const geo::Lla eye{45.7, -121.5, 1500};

}  // namespace

TEST_CASE("scene objects: a car where geo::project puts it, its shadow beside it",
          "[sim][scene][objects]") {
    const auto objects = sim::ObjectSet::all().at(0);
    const sim::ObjectState& car = object_named(objects, "car");
    const geo::CameraPose camera = aimed(eye, car.position, 2);
    const sim::I420Frame with = render(camera, objects), without = render(camera, {});
    const auto luma = [](const sim::I420Frame& f, const geo::Lla& at, const geo::CameraPose& c) {
        const auto p = projected(c, at);
        REQUIRE(p);
        return view(f).at(static_cast<int>(p->px), static_cast<int>(p->py)).y;
    };
    // About 30 px long at 2 km with a 2 degree field of view (seen a little end-on).
    const auto nose = projected(camera, beside(car, 2.3, 0));
    const auto tail = projected(camera, beside(car, -2.3, 0));
    REQUIRE(nose);
    REQUIRE(tail);
    CHECK(std::hypot(nose->px - tail->px, nose->py - tail->py) > 25);
    // The white roof at the centre; the road (asphalt) there without the car.
    const int roof = luma(with, car.position, camera);
    const int road = luma(without, car.position, camera);
    CHECK(roof > 190);
    CHECK(road < 110);
    // The white body in front of the windscreen; dark glass behind it.
    CHECK(luma(with, beside(car, 1.9, 0), camera) > 190);
    CHECK(luma(with, beside(car, 1.0, 0), camera) < 70);
    // The shadow falls to the south-east (the sun is in the north-west): on the car's right
    // (it drives east), darker than the road; nothing on its left.
    CHECK(luma(with, beside(car, 0, 1.4), camera) <
          0.7 * luma(without, beside(car, 0, 1.4), camera));
    CHECK(std::abs(luma(with, beside(car, 0, -1.4), camera) -
                   luma(without, beside(car, 0, -1.4), camera)) <= 2);
    // Ten metres behind it, the picture is the still scene's.
    CHECK(std::abs(luma(with, beside(car, -10, 0), camera) -
                   luma(without, beside(car, -10, 0), camera)) <= 1);
}

TEST_CASE("scene objects: a car under the highway's deck is hidden", "[sim][scene][objects]") {
    const auto under = sim::ObjectSet::all().at(24);
    const sim::ObjectState& convoy1 = object_named(under, "convoy1");
    REQUIRE(sim::under_deck(convoy1.xy, convoy1.level));
    const geo::CameraPose camera = aimed(eye, convoy1.position, 2);
    const sim::I420Frame with = render(camera, under), without = render(camera, {});
    // The deck hides it: around its place the picture is the one without objects.
    const auto centre = projected(camera, convoy1.position);
    REQUIRE(centre);
    const auto v = view(with), w = view(without);
    int differing = 0;
    for (int dy = -6; dy <= 6; ++dy)
        for (int dx = -20; dx <= 20; ++dx) {
            const int x = static_cast<int>(centre->px) + dx, y = static_cast<int>(centre->py) + dy;
            if (std::abs(v.at(x, y).y - w.at(x, y).y) > 1) ++differing;
        }
    CHECK(differing == 0);
    // The deck is concrete, lighter than the road.
    CHECK(v.at(static_cast<int>(centre->px), static_cast<int>(centre->py)).y > 130);
    // Two seconds earlier it is in the open, and drawn.
    const auto before = sim::ObjectSet::all().at(22);
    const sim::ObjectState& open = object_named(before, "convoy1");
    REQUIRE_FALSE(sim::under_deck(open.xy, open.level));
    const geo::CameraPose camera2 = aimed(eye, open.position, 2);
    const sim::I420Frame seen = render(camera2, before), empty = render(camera2, {});
    const auto at = projected(camera2, open.position);
    REQUIRE(at);
    const int px = static_cast<int>(at->px), py = static_cast<int>(at->py);
    CHECK(std::abs(view(seen).at(px, py).y - view(empty).at(px, py).y) > 20);
}
