// The simulated Orion's camera pose for its video (protocols/orion/sim/sim_camera.hpp): the pose
// gimbald derives from the gimbal's own telemetry, and a geopoint on a landmark puts the landmark
// at the picture's centre.
#include <catch2/catch.hpp>
#include <cmath>

#include "protocols/orion/codec/packets.hpp"
#include "protocols/orion/sim/sim_camera.hpp"
#include "protocols/viewpro/sim/viewpro_sim.hpp"
#include "scene_test_support.hpp"
#include "sim/scene_renderer.hpp"
#include "sim_harness.hpp"

using namespace scene_test;
using sim_test::decoded;
using sim_test::Harness;

namespace {

double angle_deg(const geo::Vec3& a, const geo::Vec3& b) {
    return std::acos(std::clamp(geo::dot(a, b) / (geo::norm(a) * geo::norm(b)), -1.0, 1.0)) *
           geo::rad2deg;
}

// The pose gimbald builds from a GeolocateTelemetry packet.
geo::CameraPose from_telemetry(const orion::GeolocateTelemetry& t) {
    return geo::camera_pose({t.lat * geo::rad2deg, t.lon * geo::rad2deg, t.alt},
                            {t.quat[0], t.quat[1], t.quat[2], t.quat[3]}, t.pan * geo::rad2deg,
                            t.tilt * geo::rad2deg, t.hfov * geo::rad2deg, t.vfov * geo::rad2deg);
}

}  // namespace

TEST_CASE("sim camera: the pose the gimbal's telemetry gives", "[sim][sim_camera]") {
    Harness h;
    // A rate command, so pan and tilt are somewhere unremarkable by the end.
    orion::Cmd cmd;
    cmd.cmd.mode = orion::Mode::rate;
    cmd.cmd.target = {0.3, -0.05};
    h.send_packet(cmd);
    const auto telemetry = decoded<orion::GeolocateTelemetry>(h.run(2.0, 0.1));
    REQUIRE(!telemetry.empty());
    const auto view = sim::orion_sim_camera(h.device());
    REQUIRE(view);
    // The last telemetry went out at the model's current time.
    CHECK(view->model_time_s * 1000 == Approx(telemetry.back().system_time_ms).margin(1));
    CHECK_FALSE(view->infrared);
    const geo::CameraPose pose = sim::camera_pose(*view);
    const geo::CameraPose reported = from_telemetry(telemetry.back());
    CHECK(geo::norm(geo::lla_to_ecef(pose.position) - geo::lla_to_ecef(reported.position)) < 1);
    CHECK(pose.hfov_deg == Approx(reported.hfov_deg).epsilon(1e-3));
    CHECK(pose.vfov_deg == Approx(reported.vfov_deg).epsilon(1e-3));
    for (const geo::ImagePoint p : {geo::ImagePoint{0, 0}, {1, 1}, {-1, 0.5}})
        CHECK(angle_deg(geo::image_ray_ned(pose, p), geo::image_ray_ned(reported, p)) < 0.02);
    // The line of sight is the one the gimbal ranges along.
    const auto& los = telemetry.back().los_ecef;
    REQUIRE(geo::norm({los[0], los[1], los[2]}) > 0);
    CHECK(angle_deg(geo::image_ray_ecef(pose, {0, 0}), {los[0], los[1], los[2]}) < 0.02);
    CHECK(sim::orion_camera_pose(h.device()).has_value());
}

TEST_CASE("sim camera: a geopoint on a landmark centres it in the picture", "[sim][sim_camera]") {
    const std::size_t summit = 0;
    Harness h;
    h.run(0.5);
    orion::GeopointCmd g;
    const geo::Lla target = landmark_lla(summit);
    g.target_lat = target.lat_deg * geo::deg2rad;
    g.target_lon = target.lon_deg * geo::deg2rad;
    g.target_alt = target.alt_m;
    h.send_packet(g);
    orion::CameraState zoom;
    zoom.zoom = 3;
    h.send_packet(zoom);
    h.run(6.0);
    const auto pose = sim::orion_camera_pose(h.device());
    REQUIRE(pose);
    const auto p = geo::project(*pose, target);
    REQUIRE(p);
    CHECK(std::abs(p->at.x) < 0.02);
    CHECK(std::abs(p->at.y) < 0.02);
    sim::SceneRenderer renderer;
    sim::I420Frame frame;
    REQUIRE(renderer.render(*pose, frame));
    CHECK(landmark_colour_at(view(frame).at(320, 180), 12) == summit);
}

TEST_CASE("sim camera: zoom, the infrared camera, and other devices", "[sim][sim_camera]") {
    Harness h;
    h.run(0.5);
    const auto wide = sim::orion_sim_camera(h.device());
    REQUIRE(wide);
    orion::CameraState zoom;
    zoom.zoom = 4;
    h.send_packet(zoom);
    h.run(0.2);
    const auto narrow = sim::orion_sim_camera(h.device());
    CHECK(std::tan(narrow->hfov_rad / 2) == Approx(std::tan(wide->hfov_rad / 2) / 4));
    CHECK_FALSE(sim::scene_options_for(*narrow).monochrome);
    h.send_packet(orion::CameraSwitch{1});
    h.run(0.2);
    const auto ir = sim::orion_sim_camera(h.device());
    CHECK(ir->infrared);
    CHECK(sim::scene_options_for(*ir).monochrome);
    CHECK(sim::scene_options_for(*ir).width == 640);

    const auto viewpro = sim::make_viewpro_sim();
    CHECK_FALSE(sim::orion_sim_camera(*viewpro));
    CHECK_FALSE(sim::orion_camera_pose(*viewpro));
}
