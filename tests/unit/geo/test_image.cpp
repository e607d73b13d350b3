// Image geometry (contract section 16): pixels, rays, locate and project as inverses on the
// ellipsoid and on the simulator's terrain, the corners against footprint(), aiming.
#include <catch2/catch.hpp>
#include <random>

#include "geo/image.hpp"
#include "geo/ray_march.hpp"
#include "sim/terrain.hpp"

using namespace gimbal::geo;

namespace {

double distance_m(const Lla& a, const Lla& b) {
    return norm(lla_to_ecef(a) - lla_to_ecef(b));
}

CameraPose demo_camera(double pan, double tilt, double rotation = 0) {
    const Quat mount = euler_to_quat(EulerDeg{4, -2, 30});
    return camera_pose({45.7, -121.5, 1500}, mount, pan, tilt, 40, 24, rotation);
}

}  // namespace

TEST_CASE("image: pixels and normalised coordinates", "[image]") {
    auto p = from_pixels({0, 0}, 1920, 1080);
    REQUIRE(p);
    CHECK(p->x == -1);
    CHECK(p->y == -1);
    p = from_pixels({960, 540}, 1920, 1080);
    CHECK(p->x == 0);
    CHECK(p->y == 0);
    p = from_pixels({1920, 1080}, 1920, 1080);
    CHECK(p->x == 1);
    CHECK(p->y == 1);
    const auto back = to_pixels({0.25, -0.5}, 1920, 1080);
    REQUIRE(back);
    CHECK(back->px == Approx(1200));
    CHECK(back->py == Approx(270));
    CHECK(from_pixels(*back, 1920, 1080)->x == Approx(0.25));
    CHECK_FALSE(from_pixels({1, 1}, 0, 1080));
    CHECK_FALSE(to_pixels({NAN, 0}, 1920, 1080));
}

TEST_CASE("image: rays through the image", "[image]") {
    const CameraPose c = demo_camera(20, -35);
    // The centre is the line of sight.
    const Vec3 los = rotate(c.camera_to_ned, {1, 0, 0});
    const Vec3 centre = image_ray_ned(c, {0, 0});
    CHECK(norm(los - (1.0 / norm(centre)) * centre) < 1e-12);
    // x = tan(a) / tan(hfov/2): the edges are half the field of view off the axis.
    const Vec3 right = image_ray_ned(c, {1, 0});
    CHECK(std::acos(dot(right, los) / norm(right)) * rad2deg == Approx(20));
    const Vec3 bottom = image_ray_ned(c, {0, 1});
    CHECK(std::acos(dot(bottom, los) / norm(bottom)) * rad2deg == Approx(12));
    // Image rotation turns the image's right axis towards its down axis (square fov here).
    const Quat mount{1, 0, 0, 0};
    const CameraPose square = camera_pose({45.7, -121.5, 1500}, mount, 0, -30, 30, 30);
    const CameraPose turned = camera_pose({45.7, -121.5, 1500}, mount, 0, -30, 30, 30, 90);
    CHECK(norm(image_ray_ned(turned, {1, 0}) - image_ray_ned(square, {0, 1})) < 1e-12);
    CHECK(norm(image_ray_ned(turned, {0, 0}) - image_ray_ned(square, {0, 0})) < 1e-12);
}

TEST_CASE("image: corners located on the ellipsoid are footprint()", "[image]") {
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int i = 0; i < 50; ++i) {
        const CameraPose c = demo_camera(unit(rng) * 360 - 180, -30 - unit(rng) * 60);
        const double ground = 100 + unit(rng) * 300;
        EllipsoidSurface flat(ground);
        const auto today = footprint(c, ground);
        const auto located = footprint(c, flat);
        REQUIRE(today.has_value() == located.has_value());
        if (!today) continue;
        CHECK(located->surface == SurfaceKind::ellipsoid);
        for (std::size_t k = 0; k < 4; ++k) {
            CHECK(located->corners[k].lat_deg == Approx((*today)[k].lat_deg).margin(1e-9));
            CHECK(located->corners[k].lon_deg == Approx((*today)[k].lon_deg).margin(1e-9));
            CHECK(located->corners[k].alt_m == Approx(ground).margin(1e-3));
        }
    }
}

TEST_CASE("image: locate(project(P)) is P on the ellipsoid and on terrain", "[image]") {
    auto terrain = gimbal::sim::terrain_surface();
    EllipsoidSurface flat(300);
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> unit(0, 1);
    int checked_terrain = 0, checked_flat = 0;
    for (int i = 0; i < 400; ++i) {
        const CameraPose c = demo_camera(unit(rng) * 360 - 180, -20 - unit(rng) * 70);
        const ImagePoint p{unit(rng) * 2 - 1, unit(rng) * 2 - 1};
        Surface& s = i % 2 ? static_cast<Surface&>(*terrain) : flat;
        const Location l = locate(c, p, s);
        if (l.ray.status != RayStatus::hit) continue;
        const auto proj = project(c, l.ray.point, &s);
        REQUIRE(proj);
        CHECK(proj->in_front);
        CHECK(proj->visible);
        CHECK(proj->at.x == Approx(p.x).margin(1e-6));
        CHECK(proj->at.y == Approx(p.y).margin(1e-6));
        const Location again = locate(c, proj->at, s);
        REQUIRE(again.ray.status == RayStatus::hit);
        CHECK(distance_m(again.ray.point, l.ray.point) < 0.5);
        (i % 2 ? checked_terrain : checked_flat)++;
        CHECK(l.surface == (i % 2 ? SurfaceKind::terrain : SurfaceKind::ellipsoid));
    }
    CHECK(checked_terrain > 100);
    CHECK(checked_flat > 100);
}

TEST_CASE("image: random ground points project and locate back", "[image]") {
    auto terrain = gimbal::sim::terrain_surface();
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> unit(0, 1);
    int visible = 0, hidden = 0;
    const CameraPose c = demo_camera(-10, -40);
    // Points in the box around the footprint on the terrain.
    const auto fp = footprint(c, *terrain);
    REQUIRE(fp);
    double lat_min = 90, lat_max = -90, lon_min = 180, lon_max = -180;
    for (const Lla& k : fp->corners) {
        lat_min = std::min(lat_min, k.lat_deg);
        lat_max = std::max(lat_max, k.lat_deg);
        lon_min = std::min(lon_min, k.lon_deg);
        lon_max = std::max(lon_max, k.lon_deg);
    }
    for (int i = 0; i < 3000 && visible < 200; ++i) {
        const double lat = lat_min + unit(rng) * (lat_max - lat_min);
        const double lon = lon_min + unit(rng) * (lon_max - lon_min);
        const Lla ground{lat, lon, *terrain->height(lat, lon)};
        const auto proj = project(c, ground, terrain.get());
        REQUIRE(proj);
        if (!proj->in_front || std::abs(proj->at.x) > 1 || std::abs(proj->at.y) > 1) continue;
        if (!proj->visible) {
            ++hidden;  // behind a hill
            continue;
        }
        ++visible;
        const Location l = locate(c, proj->at, *terrain);
        REQUIRE(l.ray.status == RayStatus::hit);
        CHECK(distance_m(l.ray.point, ground) < 0.5);
    }
    CHECK(visible >= 100);
}

TEST_CASE("image: points behind the camera are not visible", "[image]") {
    const CameraPose c = camera_pose({45.7, -121.5, 1500}, {1, 0, 0, 0}, 0, -30, 40, 24);
    // Looking north and down; a point to the south is behind.
    const auto behind = project(c, {45.6, -121.5, 100});
    REQUIRE(behind);
    CHECK_FALSE(behind->in_front);
    CHECK_FALSE(behind->visible);
    // Ahead but outside the field of view.
    const auto aside = project(c, {45.71, -121.3, 100});
    REQUIRE(aside);
    CHECK(aside->in_front);
    CHECK_FALSE(aside->visible);
    CHECK(aside->at.x > 1);
    CHECK_FALSE(project(c, {NAN, 0, 0}));
}

TEST_CASE("image: pan and tilt towards a point centre it", "[image]") {
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int i = 0; i < 100; ++i) {
        const Quat mount =
            euler_to_quat(EulerDeg{unit(rng) * 20 - 10, unit(rng) * 20 - 10, unit(rng) * 360});
        const Lla from{45.7, -121.5, 1500};
        const Lla to{45.7 + (unit(rng) - 0.5) * 0.2, -121.5 + (unit(rng) - 0.5) * 0.2, 200};
        const auto pt = pan_tilt_towards(mount, from, to);
        REQUIRE(pt);
        const CameraPose c = camera_pose(from, mount, pt->pan_deg, pt->tilt_deg, 30, 20);
        const auto proj = project(c, to);
        REQUIRE(proj);
        CHECK(proj->in_front);
        CHECK(proj->at.x == Approx(0).margin(1e-9));
        CHECK(proj->at.y == Approx(0).margin(1e-9));
    }
    CHECK_FALSE(pan_tilt_towards({1, 0, 0, 0}, {45, 0, 0}, {45, 0, 0}));
}

TEST_CASE("image: the centre meets the line of sight's ground; footprint on terrain", "[image]") {
    auto terrain = gimbal::sim::terrain_surface();
    const CameraPose c = demo_camera(15, -50);
    const Location centre = locate(c, {0, 0}, *terrain);
    REQUIRE(centre.ray.status == RayStatus::hit);
    const Intersection los = terrain->intersect(
        c.position, ned_to_ecef(rotate(c.camera_to_ned, {1, 0, 0}), c.position), {});
    CHECK(distance_m(los.point, centre.ray.point) < 1e-6);
    const auto fp = footprint(c, *terrain);
    REQUIRE(fp);
    CHECK(fp->surface == SurfaceKind::terrain);
    for (std::size_t k = 0; k < 4; ++k)
        CHECK(
            fp->corners[k].alt_m ==
            Approx(*terrain->height(fp->corners[k].lat_deg, fp->corners[k].lon_deg)).margin(0.01));
    // Looking at the sky: no footprint, and why.
    RayStatus why = RayStatus::hit;
    CHECK_FALSE(footprint(demo_camera(0, 30), *terrain, {}, &why));
    CHECK(why == RayStatus::no_ground);
    // An invalid camera.
    CameraPose bad = c;
    bad.hfov_deg = 0;
    CHECK(locate(bad, {0, 0}, *terrain).ray.status == RayStatus::invalid);
}

TEST_CASE("surface: marching the flat ellipsoid agrees with the closed form", "[image]") {
    // The generic march on the ellipsoid's single patch, against ray_to_surface.
    EllipsoidSurface flat(250);
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int i = 0; i < 50; ++i) {
        const Lla from{45.7, -121.5, 1000 + unit(rng) * 2000};
        const Vec3 dir = ned_to_ecef({unit(rng) - 0.5, unit(rng) - 0.5, 0.05 + unit(rng)}, from);
        const auto closed = flat.intersect(from, dir, {});
        const auto marched = march(flat, from, dir, {100000});
        REQUIRE(closed.status == RayStatus::hit);
        REQUIRE(marched.status == RayStatus::hit);
        CHECK(std::abs(closed.range_m - marched.range_m) < 0.01);
    }
}
