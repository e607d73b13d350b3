// The simulated camera's picture (sim/scene_renderer.hpp), checked on the raw I420 frame:
// landmarks where geo::project puts them, sky above the horizon, grid lines and the river where
// they lie, a nadir view the right way round, hidden landmarks hidden, determinism.
#include <catch2/catch.hpp>
#include <cmath>

#include "scene_test_support.hpp"
#include "sim/scene_renderer.hpp"

using namespace scene_test;
using sim::SceneRenderer;

namespace {

// A landmark's palette colour shifts a little with haze, and its 2x2 chroma block with its
// edge; this much is still "its colour".
constexpr int colour_tolerance = 12;

sim::I420Frame render(const geo::CameraPose& camera, sim::SceneOptions options = {}) {
    SceneRenderer renderer(options);
    sim::I420Frame frame;
    REQUIRE(renderer.render(camera, frame));
    return frame;
}

}  // namespace

TEST_CASE("scene: landmarks are drawn where geo::project puts them", "[sim][scene]") {
    const auto& marks = sim::landmarks();
    // A banked, pitched aircraft, so the mount attitude matters too.
    const geo::Quat mount = geo::euler_to_quat(geo::EulerDeg{12, -3, 40});
    int checked = 0;
    for (std::size_t i = 0; i < marks.size(); ++i)
        for (const auto& [east, north] : {std::pair{-2000.0, -1800.0}, {1500.0, 2500.0}})
            for (const double hfov : {65.8, 20.0, 4.0})
                for (const auto& [dpan, dtilt] : {std::pair{0.0, 0.0}, {0.3, -0.2}}) {
                    const geo::Lla from = ground_near(i, east, north, 0);
                    const geo::Lla eye{from.lat_deg, from.lon_deg, 1500};
                    const geo::CameraPose camera =
                        aimed(eye, landmark_lla(i), hfov, mount, dpan * hfov / 2, dtilt * hfov / 2);
                    const auto p = projected(camera, landmark_lla(i));
                    REQUIRE(p);
                    const sim::I420Frame frame = render(camera);
                    INFO(marks[i].name << " from " << east << "," << north << " hfov " << hfov
                                       << " at " << p->px << "," << p->py);
                    const int px = static_cast<int>(p->px), py = static_cast<int>(p->py);
                    CHECK(landmark_colour_at(view(frame).at(px, py), colour_tolerance) == i);
                    const auto centre = blob_centroid(view(frame), px, py, i, colour_tolerance);
                    REQUIRE(centre);
                    // Within 1 % of the image width of the projection.
                    CHECK(std::hypot(centre->first - p->px, centre->second - p->py) <= 6.4);
                    ++checked;
                }
    CHECK(checked == 60);
}

TEST_CASE("scene: sky above the horizon, ground below", "[sim][scene]") {
    // Level, looking north over the plateau (no river, no landmark in view).
    const geo::CameraPose camera =
        geo::camera_pose({45.7, -121.5, 1500}, {}, 0, 0, 65.8, vfov_for(65.8));
    const sim::I420Frame frame = render(camera);
    const auto v = view(frame);
    // Blue: every ground colour (haze included, up to 10 km) has U below 134.
    const auto sky_like = [](Pixel p) { return p.u >= 134; };
    int sky_rows = 0, ground_rows = 0;
    int previous_u = 1000;
    for (int py = 0; py < 360; ++py) {
        // The elevation of this row's rays (the same across the row: the camera is level).
        const auto ip = geo::from_pixels({320, py + 0.5}, 640, 360);
        const geo::Vec3 ray = geo::image_ray_ned(camera, *ip);
        const double elevation = std::asin(-ray.z / geo::norm(ray)) * geo::rad2deg;
        if (elevation > 1) {
            ++sky_rows;
            for (int px = 0; px < 640; ++px) {
                INFO(px << "," << py);
                REQUIRE(sky_like(v.at(px, py)));
            }
            // Bluer upwards.
            CHECK(v.at(320, py).u <= previous_u);
            previous_u = v.at(320, py).u;
        } else if (elevation < -6) {
            ++ground_rows;
            for (int px = 0; px < 640; ++px) {
                INFO(px << "," << py);
                REQUIRE_FALSE(sky_like(v.at(px, py)));
            }
        }
    }
    CHECK(sky_rows > 150);
    CHECK(ground_rows > 60);
    CHECK(v.at(320, 0).u > v.at(320, 170).u + 20);  // zenith blue against horizon haze
}

TEST_CASE("scene: grid lines on true north and east", "[sim][scene]") {
    // Straight down over the terrain's origin: the 1 km lines x = 0 and y = 0 cross at the
    // centre; 100 m lines every 100 m.
    const geo::CameraPose camera =
        geo::camera_pose({45.7, -121.5, 1500}, {}, 0, -90, 65.8, vfov_for(65.8));
    const sim::I420Frame frame = render(camera);
    const auto v = view(frame);
    const auto at_xy = [&](double x, double y) {
        const geo::LatLon ll = sim::terrain_lat_lon({x, y});
        const auto p = projected(camera, {ll.lat_deg, ll.lon_deg, sim::terrain_height_xy({x, y})});
        REQUIRE(p);
        return std::pair{static_cast<int>(p->px), static_cast<int>(p->py)};
    };
    const auto luma = [&](std::pair<int, int> p) { return v.at(p.first, p.second).y; };
    // The darkest / brightest of a pixel and its neighbours across the line.
    const auto darkest = [&](std::pair<int, int> p, int dx, int dy) {
        return std::min(
            {luma(p), luma({p.first - dx, p.second - dy}), luma({p.first + dx, p.second + dy})});
    };
    const auto brightest = [&](std::pair<int, int> p, int dx, int dy) {
        return std::max(
            {luma(p), luma({p.first - dx, p.second - dy}), luma({p.first + dx, p.second + dy})});
    };
    for (const double along : {-300.0, -150.0, 150.0, 300.0}) {
        INFO("along " << along);
        CHECK(brightest(at_xy(0, along), 1, 0) >= 180);      // x = 0 runs north-south
        CHECK(brightest(at_xy(2 * along, 0), 0, 1) >= 180);  // y = 0 runs east-west
    }
    // Plain ground half way between 100 m lines; on a line, at least a fifth darker.
    for (const auto& [x, y] :
         {std::pair{250.0, 50.0}, {-250.0, -150.0}, {450.0, 250.0}, {-450.0, 250.0}}) {
        INFO("at " << x << "," << y);
        const int plain = luma(at_xy(x, y));
        CHECK(plain < 160);
        CHECK(darkest(at_xy(x, y), 1, 0) > plain - 8);
        CHECK(darkest(at_xy(x, y), 0, 1) > plain - 8);
        CHECK(darkest(at_xy(x - 50, y), 1, 0) - 16 < 0.8 * (plain - 16));  // x = k * 100
        CHECK(darkest(at_xy(x, y + 50), 0, 1) - 16 < 0.8 * (plain - 16));  // y = k * 100
    }
    // A 1 km line is a straight north-south line: two points on it share a column.
    CHECK(std::abs(at_xy(0, -300).first - at_xy(0, 300).first) <= 1);
}

TEST_CASE("scene: a nadir view is north-up, and the river runs through the bridge",
          "[sim][scene]") {
    const std::size_t bridge = 2;
    REQUIRE(sim::landmarks()[bridge].name == "bridge");
    const geo::Lla b = landmark_lla(bridge);
    const geo::CameraPose camera =
        geo::camera_pose({b.lat_deg, b.lon_deg, 1500}, {}, 0, -90, 65.8, vfov_for(65.8));
    const sim::I420Frame frame = render(camera);
    const auto v = view(frame);
    CHECK(landmark_colour_at(v.at(320, 180), colour_tolerance) == bridge);
    // North is up and east is right.
    const auto north = projected(camera, ground_near(bridge, 0, 300));
    const auto east = projected(camera, ground_near(bridge, 300, 0));
    REQUIRE(north);
    REQUIRE(east);
    CHECK(north->py < 180 - 50);
    CHECK(std::abs(north->px - 320) < 5);
    CHECK(east->px > 320 + 50);
    CHECK(std::abs(east->py - 180) < 5);
    // Water along the river either side of the bridge, land beside it.
    const sim::Yuv water = sim::to_yuv(sim::scene::water);
    const sim::TerrainXY bxy = sim::terrain_xy(b.lat_deg, b.lon_deg);
    for (const double dx : {-450.0, -250.0, 250.0, 450.0}) {
        const double x = bxy.east_m + dx;
        const double y = sim::river_north_m(x) + 20;  // clear of the 100 m line on the river
        const geo::LatLon on = sim::terrain_lat_lon({x, y});
        const auto p = projected(camera, {on.lat_deg, on.lon_deg, sim::terrain_height_xy({x, y})});
        REQUIRE(p);
        const Pixel px = v.at(static_cast<int>(p->px), static_cast<int>(p->py));
        INFO("river at " << dx << ": " << px.y << " " << px.u << " " << px.v);
        // Water, shaded by the valley side it lies on: blue over green (U above V).
        CHECK(px.u > 135);
        CHECK(px.u > px.v + 10);
        CHECK(std::abs(px.u - water.u) < 15);
        const auto bank = projected(camera, ground_near(bridge, dx, 170));
        REQUIRE(bank);
        CHECK(v.at(static_cast<int>(bank->px), static_cast<int>(bank->py)).u < 128);
    }
}

TEST_CASE("scene: a landmark behind a hill is not drawn", "[sim][scene]") {
    // Look for a viewpoint from which the bridge, in its valley, is in frame but hidden.
    auto surface = sim::terrain_surface();
    const std::size_t bridge = 2;
    const geo::Lla target = landmark_lla(bridge);
    std::optional<geo::CameraPose> hidden;
    for (double distance = 2000; distance <= 6000 && !hidden; distance += 500)
        for (double az = 0; az < 360 && !hidden; az += 30) {
            const double a = az * geo::deg2rad;
            const geo::Lla ground =
                ground_near(bridge, distance * std::sin(a), distance * std::cos(a));
            const geo::Lla eye{ground.lat_deg, ground.lon_deg, ground.alt_m + 60};
            const geo::CameraPose camera = aimed(eye, target, 30);
            const auto p = geo::project(camera, target, surface.get());
            if (p && p->in_front && !p->visible) hidden = camera;
        }
    REQUIRE(hidden);
    const sim::I420Frame frame = render(*hidden);
    CHECK_FALSE(landmark_colour_at(view(frame).at(320, 180), 40) == bridge);
}

TEST_CASE("scene: deterministic, and only the camera changes the picture", "[sim][scene]") {
    const geo::CameraPose camera = aimed({45.69, -121.51, 1500}, landmark_lla(0), 50);
    const sim::I420Frame a = render(camera), b = render(camera);
    CHECK(a.y == b.y);
    CHECK(a.u == b.u);
    CHECK(a.v == b.v);
    SceneRenderer renderer;
    sim::I420Frame c;
    renderer.render(aimed({45.69, -121.51, 1500}, landmark_lla(1), 50), c);
    renderer.render(camera, c);  // a reused renderer and frame give the same bytes
    CHECK(c.y == a.y);
    CHECK(c.u == a.u);
    geo::CameraPose moved = camera;
    moved.position.alt_m += 10;
    CHECK(render(moved).y != a.y);
}

TEST_CASE("scene: sizes, grid, monochrome and invalid cameras", "[sim][scene]") {
    const geo::CameraPose nadir =
        geo::camera_pose({45.7, -121.5, 1500}, {}, 0, -90, 65.8, vfov_for(65.8));
    SceneRenderer renderer;
    sim::I420Frame frame;
    REQUIRE(renderer.render(nadir, frame));
    CHECK(frame.width == 640);
    CHECK(frame.height == 360);
    CHECK(frame.u.size() == 320u * 180u);
    // Smooth ground seen straight down needs only the coarse grid's rays.
    CHECK(renderer.stats().rays == 41 * 24);
    CHECK(renderer.stats().refined_cells == 0);

    sim::SceneOptions small;
    small.width = 320;
    small.height = 180;
    small.grid_px = 8;
    small.monochrome = true;
    SceneRenderer mono(small);
    REQUIRE(mono.render(nadir, frame));
    CHECK(frame.width == 320);
    CHECK(std::all_of(frame.u.begin(), frame.u.end(), [](auto c) { return c == 128; }));
    CHECK(std::all_of(frame.v.begin(), frame.v.end(), [](auto c) { return c == 128; }));
    CHECK(mono.stats().rays == 41 * 24);

    // Bad options fall back to the defaults.
    sim::SceneOptions odd;
    odd.width = 641;
    CHECK_FALSE(sim::valid(odd));
    CHECK(SceneRenderer(odd).options().width == 640);

    geo::CameraPose broken = nadir;
    broken.hfov_deg = 0;
    CHECK_FALSE(renderer.render(broken, frame));
    CHECK(frame.width == 640);
    CHECK(std::all_of(frame.y.begin(), frame.y.end(), [](auto c) { return c == 126; }));

    // A camera under the ground sees darkness, not sky.
    const double ground = sim::terrain_height(45.7, -121.5);
    REQUIRE(renderer.render(
        geo::camera_pose({45.7, -121.5, ground - 20}, {}, 0, 10, 65.8, vfov_for(65.8)), frame));
    CHECK(std::all_of(frame.y.begin(), frame.y.end(), [](auto c) { return c < 30; }));
}
