// lib/klv_state/sensor_frame with a visual track (contract section 20), on the simulated
// Orion of the gimbal-protocol fixtures (telemetry at 1500 m HAE, 1521 m MSL: undulation
// -21 m): the track's ground position becomes tags 40-42 (its height turned to MSL) and the
// track the VMTI set, in pixels of STATE video's frame; without a track, or before the frame
// size is known, the set is as before.
#include <catch2/catch.hpp>

#include "../gimbal_protocol/fixtures.hpp"
#include "klv_state/sensor_frame.hpp"

using namespace gimbal;

namespace {

state::TrackState track_at(double lat, double lon, double alt_hae) {
    state::TrackState t;
    t.id = 9;
    t.box = {-0.25, -0.25, 0.25, 0.25};
    t.centre = {0.0, 0.0};
    t.confidence = 0.5;
    t.ground = state::TrackGround{lat, lon, alt_hae};
    return t;
}

}  // namespace

TEST_CASE(
    "sensor_frame: a track's ground position is the target location and the track the "
    "VMTI set") {
    auto orion = gptest::orion_state();
    orion->video = state::VideoState{};
    orion->video->width = 1280;
    orion->video->height = 720;
    orion->visual_tracking = true;  // the view's `track`: none running yet

    const klv::SensorFrame before = klv_state::sensor_frame(orion, 1);
    REQUIRE(before.target);
    CHECK(before.target->lat_deg == 45.01);  // the gimbal's own target
    CHECK_FALSE(before.vmti);

    orion->track = track_at(45.02, -121.01, 100.0);
    const auto frame = klv_state::sensor_frame(orion, 1);
    REQUIRE(frame.target);
    CHECK(frame.target->lat_deg == 45.02);
    CHECK(frame.target->lon_deg == -121.01);
    REQUIRE(frame.target->alt_msl_m);
    CHECK(*frame.target->alt_msl_m == Approx(121.0));  // 100 m HAE, undulation -21 m
    REQUIRE(frame.frame_center);
    CHECK(frame.frame_center->lat_deg != 45.02);  // the frame centre is not the track's
    REQUIRE(frame.vmti);
    CHECK(frame.vmti->frame_width == 1280u);
    REQUIRE(frame.vmti->targets.size() == 1);
    CHECK(frame.vmti->targets[0].id == 9);
    CHECK(frame.vmti->targets[0].centroid == klv::vmti_pixel_number(361, 641, 1280));
    CHECK((frame.vmti->targets[0].location == klv::VmtiLocation{45.02, -121.01, 100.0}));
}

TEST_CASE(
    "sensor_frame: a track without ground keeps the gimbal's target; no frame size, no "
    "VMTI") {
    auto orion = gptest::orion_state();
    orion->visual_tracking = true;
    orion->track = track_at(45.02, -121.01, 100.0);
    orion->track->ground.reset();
    const auto frame = klv_state::sensor_frame(orion, 1);  // no video section
    REQUIRE(frame.target);
    CHECK(frame.target->lat_deg == 45.01);
    CHECK_FALSE(frame.vmti);

    orion->video = state::VideoState{};  // connected, size not known yet
    const auto unsized = klv_state::sensor_frame(orion, 1);
    CHECK_FALSE(unsized.vmti);
}
