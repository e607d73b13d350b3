// The simulated Viewpro's target calculation: line of sight from vehicle pose and gimbal
// angles to flat terrain, or a laser distance along it. Checked against lib/geo's look angles.
#include <catch2/catch.hpp>
#include <cmath>

#include "geo/wgs84.hpp"
#include "protocols/viewpro/sim/viewpro_sim_target.hpp"

using namespace gimbal;
using Catch::Matchers::WithinAbs;

namespace {

geo::LookAngles seen_from(const sim::ViewproPose& p, const sim::ViewproTarget& t) {
    return geo::look_angles({p.lat_deg, p.lon_deg, p.alt_msl_m},
                            {t.lat_deg, t.lon_deg, t.alt_msl_m});
}

sim::ViewproPose level_at(double alt) {
    sim::ViewproPose p;
    p.lat_deg = 47.0;
    p.lon_deg = 8.0;
    p.alt_msl_m = alt;
    return p;
}

}  // namespace

TEST_CASE("level vehicle, gimbal 45 down ahead: target ahead at the altitude's distance",
          "[sim][viewpro][target]") {
    const auto p = level_at(300);
    const auto t = sim::locate_viewpro_target(p, {-45, 0}, 0, 0);
    REQUIRE(t);
    CHECK_THAT(t->alt_msl_m, WithinAbs(0, 0.01));
    CHECK_THAT(t->range_m, WithinAbs(300 * std::sqrt(2.0), 0.5));  // the earth curves a little
    const auto look = seen_from(p, *t);
    CHECK_THAT(look.azimuth_deg, WithinAbs(0, 0.01));
    CHECK_THAT(look.elevation_deg, WithinAbs(-45, 0.05));
    CHECK_THAT(look.range_m, WithinAbs(t->range_m, 0.01));
}

TEST_CASE("heading, gimbal yaw and body attitude all turn the line of sight",
          "[sim][viewpro][target]") {
    auto p = level_at(500);
    p.yaw_deg = 90;  // flying east
    SECTION("heading plus gimbal yaw") {
        const auto t = sim::locate_viewpro_target(p, {-30, 45}, 100, 0);
        REQUIRE(t);
        const auto look = seen_from(p, *t);
        CHECK_THAT(look.azimuth_deg, WithinAbs(135, 0.01));
        CHECK_THAT(look.elevation_deg, WithinAbs(-30, 0.05));
        CHECK_THAT(t->alt_msl_m, WithinAbs(100, 0.01));
    }
    SECTION("nose up 10 degrees lifts a forward line of sight") {
        p.pitch_deg = 10;
        const auto t = sim::locate_viewpro_target(p, {-45, 0}, 0, 0);
        REQUIRE(t);
        CHECK_THAT(seen_from(p, *t).elevation_deg, WithinAbs(-35, 0.05));
        CHECK_THAT(seen_from(p, *t).azimuth_deg, WithinAbs(90, 0.01));
    }
    SECTION("right wing down 20 degrees tilts a right-looking line of sight down") {
        p.roll_deg = 20;
        const auto t = sim::locate_viewpro_target(p, {-10, 90}, 0, 0);
        REQUIRE(t);
        CHECK_THAT(seen_from(p, *t).elevation_deg, WithinAbs(-30, 0.05));
        CHECK_THAT(std::abs(seen_from(p, *t).azimuth_deg), WithinAbs(180, 0.01));  // south
    }
}

TEST_CASE("a laser distance puts the target that far along the line of sight",
          "[sim][viewpro][target]") {
    const auto p = level_at(300);
    const auto t = sim::locate_viewpro_target(p, {-30, -90}, 0, 0, 250.0);
    REQUIRE(t);
    CHECK_THAT(t->range_m, WithinAbs(250, 1e-6));
    CHECK_THAT(t->alt_msl_m, WithinAbs(300 - 125, 0.05));
    const auto look = seen_from(p, *t);
    CHECK_THAT(look.azimuth_deg, WithinAbs(-90, 0.01));
    CHECK_FALSE(sim::locate_viewpro_target(p, {-30, 0}, 0, 0, 0.0));
    CHECK_FALSE(sim::locate_viewpro_target(p, {-30, 0}, 0, 0, -5.0));
}

TEST_CASE("the geoid undulation only shifts heights", "[sim][viewpro][target]") {
    const auto p = level_at(300);
    const auto a = sim::locate_viewpro_target(p, {-45, 0}, 0, 0);
    const auto b = sim::locate_viewpro_target(p, {-45, 0}, 0, 50);
    REQUIRE(a);
    REQUIRE(b);
    CHECK_THAT(b->alt_msl_m, WithinAbs(0, 0.01));
    CHECK_THAT(b->lat_deg, WithinAbs(a->lat_deg, 1e-7));
    CHECK_THAT(b->range_m, WithinAbs(a->range_m, 0.05));
}

TEST_CASE("no target above the horizon or below the terrain", "[sim][viewpro][target]") {
    CHECK_FALSE(sim::locate_viewpro_target(level_at(300), {5, 0}, 0, 0));
    CHECK_FALSE(sim::locate_viewpro_target(level_at(300), {-45, 0}, 400, 0));
}
