// Render, time code, encode in one call (sim_video/sim_video_source.hpp).
#include <catch2/catch.hpp>

#include "../sim/scene_test_support.hpp"
#include "protocols/orion/sim/sim_camera.hpp"
#include "sim/frame_code.hpp"
#include "sim_video/annex_b.hpp"
#include "sim_video/sim_video_source.hpp"

using namespace gimbal;
using namespace gimbal::sim_video;

TEST_CASE("sim video source: a frame from a camera pose and from the Orion's view",
          "[sim_video][source]") {
    SimVideoOptions options;
    options.scene.width = 320;
    options.scene.height = 180;
    options.h264.width = 999;  // follows the scene
    auto opened = SimVideoSource::open(options);
    REQUIRE(opened);
    SimVideoSource& source = **opened;
    CHECK(source.encoder().options().width == 320);

    const geo::CameraPose camera =
        scene_test::aimed({45.69, -121.51, 1500}, scene_test::landmark_lla(0), 40);
    std::vector<AccessUnit> out;
    REQUIRE(source.frame(camera, 1735689600000ull, 0, out));
    REQUIRE(out.size() == 1);
    CHECK(out[0].key);
    CHECK(sim::decode_frame_code(source.picture()) == 1735689600000ull);
    CHECK(source.render_stats().rays > 0);

    // The infrared camera: no colour at all.
    sim::OrionCameraView ir;
    ir.position = {45.69, -121.51, 1500};
    ir.tilt_rad = -0.5;
    ir.hfov_rad = 0.3;
    ir.vfov_rad = 0.24;
    ir.infrared = true;
    REQUIRE(source.frame(sim::camera_view(ir), 1735689600067ull, 6000, out));
    CHECK(out.size() == 2);
    CHECK(std::all_of(source.picture().u.begin(), source.picture().u.end(),
                      [](auto c) { return c == 128; }));
    CHECK(sim::decode_frame_code(source.picture()) == 1735689600067ull);
    ir.infrared = false;
    REQUIRE(source.frame(sim::camera_view(ir), 1735689600133ull, 12000, out));
    CHECK_FALSE(std::all_of(source.picture().u.begin(), source.picture().u.end(),
                            [](auto c) { return c == 128; }));

    // The encoder's refusal comes back.
    CHECK_FALSE(source.frame(camera, 1735689600200ull, 12000, out));
    CHECK(source.error() == "frame time does not increase");
}

TEST_CASE("sim video source: bad options", "[sim_video][source]") {
    SimVideoOptions options;
    options.scene.width = 15;
    CHECK_FALSE(SimVideoSource::open(options));
    options = {};
    options.h264.bitrate_bps = 1;
    const auto opened = SimVideoSource::open(options);
    REQUIRE_FALSE(opened);
    CHECK(opened.error().message == "bitrate must be 50 kbit/s..50 Mbit/s");
}
