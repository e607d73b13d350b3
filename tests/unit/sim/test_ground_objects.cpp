// The simulator's moving objects (sim/ground_objects.hpp): on their roads at their speeds,
// turning round at the ends, the convoy passing under the highway's deck when the catalogue
// says, and the choice of objects by name. Their picture: tests/unit/sim/test_scene_objects.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "scene_test_support.hpp"
#include "sim/ground_objects.hpp"

using namespace gimbal;
using scene_test::object_named;
using sim::ObjectSet;

namespace {

double distance_to_road(sim::TerrainXY p, const std::string& route) {
    std::vector<sim::TerrainXY> line;
    if (route == "river") {
        for (double x = -7000; x <= 7000; x += 100) line.push_back({x, sim::river_north_m(x)});
    } else {
        for (const auto& r : sim::roads())
            if (r.name == route) line = r.points;
    }
    REQUIRE(line.size() >= 2);
    double best = 1e300;
    for (std::size_t i = 1; i < line.size(); ++i) {
        const auto a = line[i - 1], b = line[i];
        const double dx = b.east_m - a.east_m, dy = b.north_m - a.north_m;
        const double u = std::clamp(
            ((p.east_m - a.east_m) * dx + (p.north_m - a.north_m) * dy) / (dx * dx + dy * dy), 0.0,
            1.0);
        best = std::min(best,
                        std::hypot(a.east_m + u * dx - p.east_m, a.north_m + u * dy - p.north_m));
    }
    return best;
}

}  // namespace

TEST_CASE("objects: on their routes, in their lanes, at their speeds", "[sim][objects]") {
    const ObjectSet all = ObjectSet::all();
    REQUIRE(all.indices().size() == sim::object_catalogue().size());
    for (double t = 0; t <= 1200; t += 7.3) {
        for (const auto& o : all.at(t)) {
            const auto& spec = o.spec();
            INFO(spec.name << " at t " << t);
            CHECK(spec.speed_mps >= 5);
            CHECK(spec.speed_mps <= 25);
            // In its lane (the river: on its centre line), within a metre at a bend.
            CHECK(distance_to_road(o.xy, spec.route) <= spec.lane_m + 1);
            CHECK(std::hypot(o.north_mps, o.east_mps) == Approx(spec.speed_mps));
            // The nose points where it goes.
            const double h = o.heading_deg * geo::deg2rad;
            CHECK(o.east_mps == Approx(spec.speed_mps * std::sin(h)).margin(1e-6));
            CHECK(o.north_mps == Approx(spec.speed_mps * std::cos(h)).margin(1e-6));
            CHECK(o.position.alt_m == Approx(sim::terrain_height_xy(o.xy)));
        }
    }
}

TEST_CASE("objects: they move as their velocity says, and turn round at the ends",
          "[sim][objects]") {
    const ObjectSet all = ObjectSet::all();
    const double dt = 0.1;
    for (double t = 3; t < 3000; t += 61) {
        const auto now = all.at(t), next = all.at(t + dt);
        for (std::size_t i = 0; i < now.size(); ++i) {
            INFO(now[i].spec().name << " at t " << t);
            const double de = next[i].xy.east_m - now[i].xy.east_m;
            const double dn = next[i].xy.north_m - now[i].xy.north_m;
            // Unless it turns round or a corner in this step, it moves by velocity x dt.
            if (std::abs(next[i].heading_deg - now[i].heading_deg) < 1e-9) {
                CHECK(de == Approx(now[i].east_mps * dt).margin(1e-6));
                CHECK(dn == Approx(now[i].north_mps * dt).margin(1e-6));
            }
        }
    }
    // The eastbound car comes back westbound after the east end (6 km away).
    const auto at_start = all.at(0), at_800 = all.at(800);
    CHECK(object_named(at_start, "car").east_mps > 14);
    CHECK(object_named(at_800, "car").east_mps < -14);
}

TEST_CASE("objects: the convoy drives under the highway's deck on time", "[sim][objects]") {
    const ObjectSet all = ObjectSet::all();
    for (int k = 0; k < 5; ++k) {
        const std::string name = "convoy" + std::to_string(k + 1);
        const double at = 24 + 12 * k;
        INFO(name);
        const auto under = [&](double t) {
            const auto objects = all.at(t);
            const auto& o = object_named(objects, name);
            CHECK(o.east_mps < -14);  // westbound
            return sim::under_deck(o.xy, o.level);
        };
        CHECK(under(at));
        CHECK(under(at - 0.8));
        CHECK(under(at + 0.8));
        CHECK_FALSE(under(at - 1.2));
        CHECK_FALSE(under(at + 1.2));
    }
    // What drives on the deck is not under it; the boat never is.
    for (double t = 0; t < 600; t += 10) {
        const auto objects = all.at(t);
        CHECK_FALSE(sim::under_deck(object_named(objects, "truck").xy,
                                    object_named(objects, "truck").level));
        CHECK_FALSE(sim::under_deck(object_named(objects, "boat").xy, 0));
    }
}

TEST_CASE("objects: chosen by name", "[sim][objects]") {
    std::string why;
    const auto none = ObjectSet::parse("none", why);
    REQUIRE(none);
    CHECK(none->empty());
    CHECK(none->at(10).empty());
    const auto some = ObjectSet::parse("boat,car", why);
    REQUIRE(some);
    const auto objects = some->at(0);
    REQUIRE(objects.size() == 2);
    CHECK(objects[0].spec().name == "boat");
    CHECK(objects[1].spec().name == "car");
    CHECK(sim::to_string(objects[0].spec().kind) == "boat");
    CHECK_FALSE(ObjectSet::parse("car,bus", why));
    CHECK(why.find("unknown object 'bus'") != std::string::npos);
    CHECK(why.find("convoy3") != std::string::npos);
    CHECK_FALSE(ObjectSet::parse("car,car", why));
    CHECK(why.find("twice") != std::string::npos);
    CHECK_FALSE(ObjectSet::parse("", why));
    CHECK_FALSE(ObjectSet::parse("car,", why));
    // The same time gives the same places.
    const auto a = ObjectSet::all().at(123.4), b = ObjectSet::all().at(123.4);
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].xy.east_m == b[i].xy.east_m);
        CHECK(a[i].xy.north_m == b[i].xy.north_m);
    }
}
