// lib/klv_state/track_vmti and the generated set's tag 74 (contract section 20): a track's
// image coordinates (-1..1, x right, y down) become 1-based pixels of the stream's frame, its
// confidence percent, its ground position the VMTI location; sensor_set() carries it as tag 74.
#include <catch2/catch.hpp>
#include <cmath>

#include "klv/local_set.hpp"
#include "klv/sensor_set.hpp"
#include "klv_state/track_vmti.hpp"

using namespace gimbal;

namespace {

state::TrackState sample_track() {
    state::TrackState t;
    t.id = 42;
    t.box = {-0.1875, -1.0 / 6.0, 0.1, 1.0 / 6.0};
    t.centre = {0.0, 0.0};
    t.confidence = 0.874;
    t.ground = state::TrackGround{47.5, 8.25, 400.0};
    return t;
}

}  // namespace

TEST_CASE("image coordinates become 1-based pixel indices, held to the frame") {
    CHECK(klv_state::pixel_index(-1.0, 1280) == 1);
    CHECK(klv_state::pixel_index(0.0, 1280) == 641);  // the right one of the middle two
    CHECK(klv_state::pixel_index(1.0, 1280) == 1280);
    CHECK(klv_state::pixel_index(-1.5, 1280) == 1);
    CHECK(klv_state::pixel_index(3.0, 1280) == 1280);
    CHECK(klv_state::pixel_index(std::nan(""), 1280) == 1);
    CHECK(klv_state::pixel_index(1.0 / 6.0, 720) == 421);
}

TEST_CASE("a track becomes one VMTI target in pixels of the frame") {
    const auto vmti = klv_state::track_vmti(sample_track(), 1280, 720);
    REQUIRE(vmti);
    CHECK(vmti->frame_width == 1280u);
    CHECK(vmti->frame_height == 720u);
    CHECK(vmti->total_targets == 1u);
    CHECK(vmti->reported_targets == 1u);
    REQUIRE(vmti->targets.size() == 1);
    const klv::VmtiTarget& t = vmti->targets[0];
    CHECK(t.id == 42);
    CHECK(t.centroid == klv::vmti_pixel_number(361, 641, 1280));
    CHECK(t.top_left == klv::vmti_pixel_number(301, 521, 1280));
    CHECK(t.bottom_right == klv::vmti_pixel_number(421, 705, 1280));
    CHECK(t.confidence_pct == 87);
    CHECK((t.location == klv::VmtiLocation{47.5, 8.25, 400.0}));
}

TEST_CASE("a track's box corners are ordered, its confidence held to 0..100") {
    state::TrackState track = sample_track();
    std::swap(track.box.x0, track.box.x1);
    std::swap(track.box.y0, track.box.y1);
    track.confidence = 1.7;
    track.ground.reset();
    const auto vmti = klv_state::track_vmti(track, 1280, 720);
    REQUIRE(vmti);
    CHECK(vmti->targets[0].top_left == klv::vmti_pixel_number(301, 521, 1280));
    CHECK(vmti->targets[0].confidence_pct == 100);
    CHECK_FALSE(vmti->targets[0].location);
}

TEST_CASE("no VMTI before the frame size is known") {
    CHECK_FALSE(klv_state::track_vmti(sample_track(), std::nullopt, 720));
    CHECK_FALSE(klv_state::track_vmti(sample_track(), 1280, 0));
}

TEST_CASE("the generated set carries the VMTI set as tag 74 and the target as 40-42") {
    klv::SensorFrame frame;
    frame.time_us = 1'700'000'000'000'000;
    frame.sensor_lat_deg = 47.4;
    frame.sensor_lon_deg = 8.2;
    frame.target = klv::GroundPoint{47.5, 8.25, 352.0};
    frame.vmti = klv_state::track_vmti(sample_track(), 1280, 720);
    const klv::Encoded e = klv::encode(klv::sensor_set(frame));
    REQUIRE(e.ok());
    const klv::DecodeResult r = klv::decode(e.value());
    REQUIRE(r.ok());
    CHECK(r.json["target_location_latitude"].get<double>() == Approx(47.5).margin(1e-6));
    CHECK(r.json["target_location_elevation"].get<double>() == Approx(352.0).margin(0.2));
    const auto& vmti = r.json["vmti"];
    REQUIRE(vmti["targets"].size() == 1);
    CHECK(vmti["targets"][0]["id"] == 42);
    CHECK(vmti["targets"][0]["centroid"]["row"] == 361);
    CHECK(vmti["targets"][0]["centroid"]["column"] == 641);
    CHECK(vmti["targets"][0]["location"]["lat"] == 47.5);

    frame.vmti.reset();
    const klv::DecodeResult without = klv::decode(klv::encode(klv::sensor_set(frame)).value());
    REQUIRE(without.ok());
    CHECK_FALSE(without.json.contains("vmti"));
}
