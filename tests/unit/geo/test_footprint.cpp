// Camera footprint: image-corner rays meeting the ellipsoid raised to the ground altitude.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "geo/footprint.hpp"

using namespace gimbal::geo;

namespace {

const Lla gorge{45.7, -121.5, 1000.0};

// Straight-line distance between two corners on the surface at alt_m.
double distance_m(const LatLon& a, const LatLon& b, double alt_m) {
    return norm(lla_to_ecef({a.lat_deg, a.lon_deg, alt_m}) -
                lla_to_ecef({b.lat_deg, b.lon_deg, alt_m}));
}

CameraPose nadir(Lla at, double hfov_deg, double vfov_deg) {
    // Pitch -90 turns the line of sight straight down; the image's top is then north.
    return {at, euler_to_quat(EulerDeg{0, -90, 0}), hfov_deg, vfov_deg};
}

}  // namespace

TEST_CASE("a nadir camera 1,000 m above flat ground sees 1,154.7 m x 727.9 m", "[geo][footprint]") {
    const auto fp = footprint(nadir(gorge, 60, 40), 0.0);
    REQUIRE(fp);
    const auto& [tl, tr, br, bl] = *fp;
    // 2 * 1000 * tan(30 deg) and 2 * 1000 * tan(20 deg); the ellipsoid's curvature adds
    // centimetres over a kilometre.
    CHECK(distance_m(tl, tr, 0) == Approx(1154.70).margin(0.3));
    CHECK(distance_m(bl, br, 0) == Approx(1154.70).margin(0.3));
    CHECK(distance_m(tr, br, 0) == Approx(727.94).margin(0.3));
    CHECK(distance_m(tl, bl, 0) == Approx(727.94).margin(0.3));
    // Image top is north, image right is east.
    CHECK(tl.lat_deg > bl.lat_deg);
    CHECK(tr.lon_deg > tl.lon_deg);
    CHECK(br.lat_deg < tr.lat_deg);
    // Centred under the camera.
    CHECK((tl.lat_deg + br.lat_deg) / 2 == Approx(gorge.lat_deg).margin(1e-7));
    CHECK((tl.lon_deg + br.lon_deg) / 2 == Approx(gorge.lon_deg).margin(1e-7));
}

TEST_CASE("the ground may be above the ellipsoid", "[geo][footprint]") {
    // 1,000 m above ground that is 2,500 m above the ellipsoid: the same rectangle.
    const auto fp = footprint(nadir({45.7, -121.5, 3500}, 60, 40), 2500);
    REQUIRE(fp);
    CHECK(distance_m((*fp)[0], (*fp)[1], 2500) == Approx(1154.70).margin(0.3));
    CHECK(distance_m((*fp)[1], (*fp)[2], 2500) == Approx(727.94).margin(0.3));
}

TEST_CASE("a camera 10 degrees below the horizon", "[geo][footprint]") {
    const Quat look = euler_to_quat(EulerDeg{0, -10, 30});  // heading 030, 10 below horizon
    const CameraPose camera{gorge, look, 6, 4};
    const auto fp = footprint(camera, 0);
    REQUIRE(fp);
    // Each corner lies where its ray says: seen from the camera at the ray's own elevation
    // and azimuth, on the ground.
    const double r = std::tan(3 * deg2rad), d = std::tan(2 * deg2rad);
    const Vec3 rays[4] = {{1, -r, -d}, {1, r, -d}, {1, r, d}, {1, -r, d}};
    for (std::size_t i = 0; i < 4; ++i) {
        const Vec3 ned = rotate(look, rays[i]);
        const double elevation = std::atan2(-ned.z, std::hypot(ned.x, ned.y)) * rad2deg;
        const double azimuth = std::atan2(ned.y, ned.x) * rad2deg;
        const auto seen = look_angles(gorge, {(*fp)[i].lat_deg, (*fp)[i].lon_deg, 0});
        CHECK(seen.elevation_deg == Approx(elevation).margin(1e-6));
        CHECK(seen.azimuth_deg == Approx(azimuth).margin(1e-6));
    }
    // The far edge (8 degrees down) lies further than the near edge (12 degrees down):
    // roughly 1000 / tan(8) = 7.1 km against 1000 / tan(12) = 4.7 km on flat ground.
    const double far = look_angles(gorge, {(*fp)[0].lat_deg, (*fp)[0].lon_deg, 0}).range_m;
    const double near = look_angles(gorge, {(*fp)[3].lat_deg, (*fp)[3].lon_deg, 0}).range_m;
    CHECK(far == Approx(1000 / std::sin(8 * deg2rad)).epsilon(0.02));
    CHECK(near == Approx(1000 / std::sin(12 * deg2rad)).epsilon(0.02));
}

TEST_CASE("a corner ray above the horizon gives no footprint", "[geo][footprint]") {
    // Looking 1 degree down with a 4 degree vertical field: the top edge points up.
    CHECK_FALSE(footprint({gorge, euler_to_quat(EulerDeg{0, -1, 0}), 6, 4}, 0));
    CHECK_FALSE(footprint({gorge, euler_to_quat(EulerDeg{0, 5, 0}), 6, 4}, 0));
    CHECK(footprint({gorge, euler_to_quat(EulerDeg{0, -5, 0}), 6, 4}, 0));
    // From 1,000 m the horizon dips 1.015 degrees: a ray 1 degree down passes over the
    // curved earth, one 1.1 degrees down meets it about 90 km away.
    const Vec3 one_degree_down = ned_to_ecef({1, 0, std::tan(1.0 * deg2rad)}, gorge);
    CHECK_FALSE(ray_to_surface(gorge, one_degree_down, 0));
    const auto far = ray_to_surface(gorge, ned_to_ecef({1, 0, std::tan(1.1 * deg2rad)}, gorge), 0);
    REQUIRE(far);
    CHECK(look_angles(gorge, *far).range_m == Approx(90000).epsilon(0.2));
}

TEST_CASE("no footprint from below the ground or with a nonsense camera", "[geo][footprint]") {
    CHECK_FALSE(footprint(nadir(gorge, 60, 40), 1000));
    CHECK_FALSE(footprint(nadir(gorge, 60, 40), 1500));
    CHECK_FALSE(footprint(nadir(gorge, 0, 40), 0));
    CHECK_FALSE(footprint(nadir(gorge, 60, 180), 0));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_FALSE(footprint(nadir({nan, 0, 1000}, 60, 40), 0));
    CHECK_FALSE(footprint({gorge, {nan, 0, 0, 0}, 60, 40}, 0));
    CHECK_FALSE(footprint(nadir(gorge, 60, 40), nan));
}

TEST_CASE("Orion pan and tilt turn the mount's frame", "[geo][footprint]") {
    // Mount pointing north, pan 90 and tilt -30 looks like a mount pointing east, tilt -30.
    const Quat panned = line_of_sight_attitude(Quat{}, 90, -30);
    const Quat turned = line_of_sight_attitude(euler_to_quat(EulerDeg{0, 0, 90}), 0, -30);
    const auto a = footprint({gorge, panned, 20, 15}, 0);
    const auto b = footprint({gorge, turned, 20, 15}, 0);
    REQUIRE(a);
    REQUIRE(b);
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK((*a)[i].lat_deg == Approx((*b)[i].lat_deg).margin(1e-9));
        CHECK((*a)[i].lon_deg == Approx((*b)[i].lon_deg).margin(1e-9));
    }
    // The centre of the image is east of the camera.
    CHECK((*a)[0].lon_deg > gorge.lon_deg);
    CHECK((*a)[2].lon_deg > gorge.lon_deg);
}

TEST_CASE("a ray meets the raised surface at its altitude", "[geo][footprint]") {
    const Lla from{-33.9, 151.2, 12000};
    const Vec3 dir = ned_to_ecef({0.8, -0.3, 0.5}, from);
    const auto hit = ray_to_surface(from, dir, 350);
    REQUIRE(hit);
    CHECK(hit->alt_m == Approx(350).margin(1e-3));
    CHECK_FALSE(ray_to_surface(from, {0, 0, 0}, 0));
    CHECK_FALSE(ray_to_surface(from, ned_to_ecef({0, 0, -1}, from), 0));  // straight up
}
