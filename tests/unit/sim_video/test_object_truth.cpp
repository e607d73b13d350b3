// The moving objects' truth as the camera sees them (sim_video/object_truth.hpp) and its
// JSON lines (objects_log.hpp, gimbal-sim --objects-log).
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../sim/scene_test_support.hpp"
#include "geo/image.hpp"
#include "sim_video/object_truth.hpp"
#include "sim_video/objects_log.hpp"

using namespace gimbal;
using scene_test::object_named;

namespace {

const geo::Lla eye{45.7, -121.5, 1500};

geo::CameraPose looking_at(const geo::Lla& target, double hfov_deg) {
    const auto pt = geo::pan_tilt_towards({}, eye, target);
    REQUIRE(pt);
    const double vfov =
        2 * std::atan(std::tan(hfov_deg * geo::deg2rad / 2) * 360 / 640) * geo::rad2deg;
    return geo::camera_pose(eye, {}, pt->pan_deg, pt->tilt_deg, hfov_deg, vfov);
}

const sim_video::ObjectTruth& named(const std::vector<sim_video::ObjectTruth>& all,
                                    const std::string& name) {
    for (const auto& t : all)
        if (t.state.spec().name == name) return t;
    FAIL("no object " << name);
    return all.front();
}

}  // namespace

TEST_CASE("object truth: where the camera sees each object", "[sim_video][objects]") {
    const auto objects = sim::ObjectSet::all().at(0);
    const sim::ObjectState* car = &object_named(objects, "car");
    const geo::CameraPose camera = looking_at(car->position, 2);
    const auto truth = sim_video::object_truth(camera, objects);
    REQUIRE(truth.size() == objects.size());
    const auto& t = named(truth, "car");
    REQUIRE(t.at);
    CHECK(std::abs(t.at->x) < 1e-6);
    CHECK(std::abs(t.at->y) < 1e-6);
    CHECK(t.in_picture);
    CHECK(t.visible_fraction == 1.0);
    CHECK(t.hidden == sim_video::ObjectTruth::Hidden::no);
    REQUIRE(t.box);
    CHECK(t.box->x0 < -0.02);
    CHECK(t.box->x1 > 0.02);
    CHECK(t.box->y0 < 0);
    CHECK(t.box->y1 > 0);
    CHECK(t.slant_range_m ==
          Approx(geo::norm(geo::lla_to_ecef(car->position) - geo::lla_to_ecef(eye))));
    // Far outside a 2 degree picture.
    CHECK_FALSE(named(truth, "boat").in_picture);
    CHECK(named(truth, "boat").visible_fraction == 0.0);
}

TEST_CASE("object truth: under the deck, hidden", "[sim_video][objects]") {
    const auto objects = sim::ObjectSet::all().at(24);
    const sim::ObjectState* convoy = &object_named(objects, "convoy1");
    const auto truth = sim_video::object_truth(looking_at(convoy->position, 2), objects);
    const auto& t = named(truth, "convoy1");
    CHECK(t.in_picture);
    CHECK(t.hidden == sim_video::ObjectTruth::Hidden::deck);
    CHECK(t.visible_fraction == 0.0);
}

TEST_CASE("object truth: behind the terrain, hidden", "[sim_video][objects]") {
    // From low down west of the east hill, the hill road behind it is out of sight.
    const auto objects = sim::ObjectSet::all().at(0);
    const sim::ObjectState* hill_car = &object_named(objects, "hill_car");
    const sim::TerrainXY low{0, 2200};
    const geo::LatLon ll = sim::terrain_lat_lon(low);
    const geo::Lla from{ll.lat_deg, ll.lon_deg, sim::terrain_height_xy(low) + 30};
    const auto pt = geo::pan_tilt_towards({}, from, hill_car->position);
    REQUIRE(pt);
    const geo::CameraPose camera = geo::camera_pose(from, {}, pt->pan_deg, pt->tilt_deg, 10, 5.6);
    const auto& t = named(sim_video::object_truth(camera, objects), "hill_car");
    CHECK(t.in_picture);
    CHECK(t.hidden == sim_video::ObjectTruth::Hidden::terrain);
    CHECK(t.visible_fraction == 0.0);
}

TEST_CASE("objects log: a JSON line per object with the frame's stamp", "[sim_video][objects]") {
    const auto objects = sim::ObjectSet::all().at(24);
    const auto truth = sim_video::object_truth(looking_at(objects.front().position, 2), objects);
    const std::string text =
        sim_video::objects_log_lines({7, 1'700'000'000'000'000, 90'000 + 42'000, 24.0}, truth);
    std::istringstream lines(text);
    std::string line;
    std::size_t n = 0;
    while (std::getline(lines, line)) {
        const auto j = nlohmann::json::parse(line);
        const auto& t = truth[n];
        CHECK(j["frame"] == 7);
        CHECK(j["unix_us"] == 1'700'000'000'000'000ULL);
        CHECK(j["pts_90k"] == 132'000);
        CHECK(j["t"] == 24.0);
        CHECK(j["name"] == t.state.spec().name);
        CHECK(j["lat"].get<double>() == t.state.position.lat_deg);
        CHECK(j["heading"].get<double>() == t.state.heading_deg);
        CHECK(j["speed"].get<double>() == t.state.speed_mps);
        CHECK(j["in_picture"] == t.in_picture);
        CHECK(j["visible"].get<double>() == t.visible_fraction);
        CHECK(j["x"].is_null() == !t.at.has_value());
        CHECK(j["box"].is_null() == !t.box.has_value());
        if (t.state.spec().name == "convoy1") CHECK(j["hidden"] == "deck");
        ++n;
    }
    CHECK(n == truth.size());
    CHECK(text.back() == '\n');
}
