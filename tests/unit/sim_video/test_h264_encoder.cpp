// The H.264 encoder wrapper (sim_video/h264_encoder.hpp) in process: one access unit per
// frame at once, AUD first, SPS and PPS before each IDR, the key-frame interval, the codec
// string, the bitrate, and what it refuses.
#include <catch2/catch.hpp>

#include "../sim/scene_test_support.hpp"
#include "sim/frame_code.hpp"
#include "sim/scene_renderer.hpp"
#include "sim_video/annex_b.hpp"
#include "sim_video/h264_encoder.hpp"

using namespace gimbal;
using namespace gimbal::sim_video;

namespace {

// A camera flying east at 25 m/s, looking ahead and down at 15 fps.
geo::CameraPose flying(int frame) {
    const geo::LatLon ll = sim::terrain_lat_lon({-1500 + 25.0 * frame / 15, -500});
    return geo::camera_pose({ll.lat_deg, ll.lon_deg, 1500},
                            geo::euler_to_quat(geo::EulerDeg{0, 0, 90}), 0, -35, 50,
                            scene_test::vfov_for(50));
}

std::vector<std::uint8_t> types(const AccessUnit& unit) {
    std::vector<std::uint8_t> out;
    for (const auto& n : nal_units(unit.annex_b)) out.push_back(n.type);
    return out;
}

bool contains(const std::vector<std::uint8_t>& v, NalType t) {
    return std::find(v.begin(), v.end(), static_cast<std::uint8_t>(t)) != v.end();
}

}  // namespace

TEST_CASE("h264: one access unit per frame, key frames with their parameter sets",
          "[sim_video][h264]") {
    H264Options options;  // 640x360, 15 fps, 1 s key interval
    auto opened = H264Encoder::open(options);
    REQUIRE(opened);
    H264Encoder& encoder = **opened;
    CHECK(encoder.key_interval_frames() == 15);
    sim::SceneRenderer renderer;
    sim::I420Frame frame;
    std::size_t bytes = 0;
    const int frames = 45;
    for (int i = 0; i < frames; ++i) {
        renderer.render(flying(i), frame);
        sim::draw_frame_code(frame, 1735689600000ull + static_cast<std::uint64_t>(i) * 1000 / 15);
        std::vector<AccessUnit> out;
        REQUIRE(encoder.encode(frame, 90000 + i * 6000, out));
        // Zero latency: this frame comes out now, alone.
        REQUIRE(out.size() == 1);
        const AccessUnit& unit = out.front();
        CHECK(unit.pts_90k == 90000 + i * 6000);
        const bool key = i % 15 == 0;
        CHECK(unit.key == key);
        const auto t = types(unit);
        REQUIRE(!t.empty());
        CHECK(t.front() == static_cast<std::uint8_t>(NalType::aud));
        CHECK(contains(t, NalType::sps) == key);
        CHECK(contains(t, NalType::pps) == key);
        CHECK(contains(t, NalType::idr_slice) == key);
        CHECK(contains(t, NalType::slice) == !key);
        if (key) {
            // SPS and PPS come before the picture.
            const auto sps = std::find(t.begin(), t.end(), 7),
                       idr = std::find(t.begin(), t.end(), 5);
            CHECK(sps < idr);
            CHECK(avc_codec_string(unit.annex_b) == "avc1.42C01E");  // constrained baseline 3.0
        }
        bytes += unit.annex_b.size();
    }
    std::vector<AccessUnit> rest;
    CHECK(encoder.flush(rest));
    CHECK(rest.empty());
    // Three seconds at 1.2 Mbit/s: rate control keeps it near (the first key frame and the
    // encoder settling allow some slack).
    const double bitrate = static_cast<double>(bytes) * 8 / 3;
    INFO("bitrate " << bitrate);
    CHECK(bitrate > 0.4 * options.bitrate_bps);
    CHECK(bitrate < 1.3 * options.bitrate_bps);
    CHECK_FALSE(encoder.encode(frame, 90000 + frames * 6000, rest));  // flushed
}

TEST_CASE("h264: main profile, other sizes and key intervals", "[sim_video][h264]") {
    H264Options options;
    options.width = 320;
    options.height = 180;
    options.fps = 10;
    options.key_interval_s = 0.5;
    options.profile = "main";  // x264's profile is a ceiling: main with CABAC from veryfast
    auto opened = H264Encoder::open(options);
    REQUIRE(opened);
    CHECK((*opened)->key_interval_frames() == 5);
    sim::SceneOptions scene;
    scene.width = 320;
    scene.height = 180;
    sim::SceneRenderer renderer(scene);
    sim::I420Frame frame;
    std::vector<AccessUnit> out;
    for (int i = 0; i < 12; ++i) {
        renderer.render(flying(i), frame);
        REQUIRE((*opened)->encode(frame, i * 9000, out));
    }
    REQUIRE(out.size() == 12);
    for (std::size_t i = 0; i < out.size(); ++i) CHECK(out[i].key == (i % 5 == 0));
    CHECK(avc_codec_string(out.front().annex_b) == "avc1.4D401E");

    // ultrafast leaves out CABAC: baseline again, whatever the ceiling.
    options.preset = "ultrafast";
    opened = H264Encoder::open(options);
    REQUIRE(opened);
    out.clear();
    REQUIRE((*opened)->encode(frame, 0, out));
    CHECK(avc_codec_string(out.front().annex_b) == "avc1.42C01E");
}

TEST_CASE("h264: what the encoder refuses", "[sim_video][h264]") {
    H264Options bad;
    bad.width = 641;
    CHECK(check(bad) == "width and height must be even, 16..4096");
    CHECK(H264Encoder::open(bad).error().message == check(bad));
    bad = {};
    bad.fps = 0;
    CHECK_FALSE(check(bad).empty());
    bad = {};
    bad.bitrate_bps = 1000;
    CHECK_FALSE(check(bad).empty());
    bad = {};
    bad.key_interval_s = 0;
    CHECK_FALSE(check(bad).empty());
    bad = {};
    bad.preset = "placebo";
    CHECK_FALSE(check(bad).empty());
    bad = {};
    bad.profile = "high10";
    CHECK_FALSE(check(bad).empty());
    CHECK(check({}).empty());

    auto opened = H264Encoder::open({});
    REQUIRE(opened);
    H264Encoder& encoder = **opened;
    sim::I420Frame frame;
    REQUIRE(frame.resize(640, 360));
    std::fill(frame.y.begin(), frame.y.end(), std::uint8_t{100});
    std::fill(frame.u.begin(), frame.u.end(), std::uint8_t{128});
    std::fill(frame.v.begin(), frame.v.end(), std::uint8_t{128});
    std::vector<AccessUnit> out;
    REQUIRE(encoder.encode(frame, 1000, out));
    CHECK(out.size() == 1);
    // Time must move on.
    CHECK_FALSE(encoder.encode(frame, 1000, out));
    CHECK(encoder.error() == "frame time does not increase");
    CHECK_FALSE(encoder.encode(frame, 500, out));
    // The size is fixed at open.
    sim::I420Frame small;
    REQUIRE(small.resize(320, 180));
    CHECK_FALSE(encoder.encode(small, 2000, out));
    CHECK(encoder.error() == "frame is not 640x360 I420");
    CHECK(out.size() == 1);  // nothing appended by the refusals
    REQUIRE(encoder.encode(frame, 2000, out));
    CHECK(out.size() == 2);
}
