// The camera component's mapping (contract section 16): what QGroundControl's camera manager
// and MAVSDK's Camera plugin ask, and click-to-track as `point` with stare.
#include <catch2/catch.hpp>

#include "fixtures.hpp"
#include "gimbal_protocol/camera.hpp"

using namespace gptest;
namespace cc = mav::camera_cmd;

namespace {

std::vector<ExposedCamera> cameras() {
    const auto gimbals = two_gimbals();
    ExposedCamera orion;
    orion.gimbal = gimbals[0];
    orion.component_id = camera_component(gimbals[0].device_id);
    orion.video = true;
    orion.can_point = orion.can_zoom = true;
    orion.streams = {{"main", "15010", mav::video_stream::type_mpeg_ts},
                     {"main 2", "mpegts://239.1.2.3:5600", mav::video_stream::type_mpeg_ts}};
    ExposedCamera viewpro;
    viewpro.gimbal = gimbals[1];
    viewpro.component_id = camera_component(gimbals[1].device_id);
    return {orion, viewpro};
}

Fixture<OrionGimbal> orion_with_video() {
    auto s = orion_state();
    gimbal::state::VideoState v;
    v.connected = true;
    v.codec = "h264";
    v.width = 1280;
    v.height = 720;
    v.fps = 30.0;
    v.bitrate_bps = 4000000;
    s->video = v;
    return s;
}

std::string text(const auto& bytes) {
    std::string out;
    for (const auto b : bytes) {
        if (b == 0) break;
        out.push_back(static_cast<char>(b));
    }
    return out;
}

}  // namespace

TEST_CASE("each gimbal's camera is component 100 + device id - 1, a MAV_TYPE_CAMERA") {
    CHECK(camera_component(1) == 100);
    CHECK(camera_component(6) == 105);
    const auto hb = camera_heartbeat();
    CHECK(hb.type == mav::mav_type_camera);
    CHECK(hb.autopilot == mav::mav_autopilot_invalid);
    CameraComponents c(cameras());
    CHECK(c.owns(100));
    CHECK(c.owns(101));
    CHECK_FALSE(c.owns(102));
    CHECK_FALSE(c.owns(154));
}

TEST_CASE("CAMERA_INFORMATION: flags from the capabilities and the video, device ids") {
    const auto cams = cameras();
    const auto orion = camera_component_information(cams[0], orion_state(), 7);
    namespace f = mav::camera_cap;
    CHECK(orion.flags == (f::has_basic_zoom | f::has_video_stream | f::has_tracking_point |
                          f::has_tracking_geo_status));
    CHECK(orion.gimbal_device_id == 1);
    CHECK(orion.camera_device_id == 0);
    CHECK(text(orion.vendor_name) == "Trillium");
    CHECK(orion.resolution_h == 1920);
    const auto viewpro = camera_component_information(cams[1], viewpro_state(), 7);
    CHECK(viewpro.flags == 0);
    CHECK(viewpro.gimbal_device_id == 2);
}

TEST_CASE("a gimbal that reports its maker is announced by it, not by a protocol's name") {
    // A MAVLink gimbal device names itself in STATE `device` (GIMBAL_DEVICE_INFORMATION).
    const ExposedGimbal device{"gremsy", "mavlink", 3, 172};
    const auto state = empty_device();
    gimbal::mavlink::GimbalDeviceInformation named;
    mav::set_text(named.vendor_name, "Gremsy");
    mav::set_text(named.model_name, "T3V3");
    state->data.information = named;
    const auto info = device_information(device, state, 7);
    CHECK(text(info.vendor_name) == "Gremsy");
    CHECK(text(info.model_name) == "T3V3");
    const auto camera = camera_information(device, state, 7);
    CHECK(text(camera.vendor_name) == "Gremsy");
    // Not reported yet: the protocol's own maker, never another protocol's.
    const auto unnamed = device_information(device, empty_device(), 7);
    CHECK(text(unnamed.vendor_name) == "MAVLink");
    CHECK(text(device_information({"main", "orion", 1, 154}, empty_orion(), 7).vendor_name) ==
          "Trillium");
}

TEST_CASE("TRACK_POINT: MAVLink's 0..1 becomes point x, y -1..1 with stare") {
    CameraComponents c(cameras());
    const auto cam = *c.find(100);
    const auto out = c.command(
        long_cmd(cc::camera_track_point, {0.7f, 0.4f, 0.05f, 0, 0, 0, 0}, 100), cam, states(), 0);
    CHECK(out.track == TrackChange::start);
    CHECK(out.radius == 0.05f);
    REQUIRE(out.mapped.requests.size() == 1);
    const auto& r = out.mapped.requests[0].request;
    CHECK(r["cmd"] == "point");
    CHECK(r["gimbal"] == "main");
    CHECK(r["x"].get<double>() == Approx(0.4).margin(1e-6));
    CHECK(r["y"].get<double>() == Approx(-0.2).margin(1e-6));
    CHECK(r["stare"] == true);
    // Corners: 0,0 is the top left.
    const auto corner = c.command(long_cmd(cc::camera_track_point, {0, 1, NaN, 100, 0, 0, 0}, 100),
                                  cam, states(), 0);
    REQUIRE(corner.mapped.requests.size() == 1);
    CHECK(corner.mapped.requests[0].request["x"] == -1.0);
    CHECK(corner.mapped.requests[0].request["y"] == 1.0);
    CHECK(std::isnan(corner.radius));
}

TEST_CASE("TRACK_POINT refusals change nothing") {
    CameraComponents c(cameras());
    const auto cam = *c.find(100);
    for (const auto& p : {std::array<float, 7>{1.5f, 0.5f, 0, 0, 0, 0, 0},
                          std::array<float, 7>{NaN, 0.5f, 0, 0, 0, 0, 0},
                          std::array<float, 7>{0.5f, -0.1f, 0, 0, 0, 0, 0},
                          std::array<float, 7>{0.5f, Inf, 0, 0, 0, 0, 0},
                          std::array<float, 7>{0.5f, 0.5f, 0, 101, 0, 0, 0}}) {
        const auto out = c.command(long_cmd(cc::camera_track_point, p, 100), cam, states(), 0);
        CHECK(out.mapped.result == MavResult::denied);
        CHECK(out.mapped.requests.empty());
        CHECK(out.track == TrackChange::none);
    }
    const auto viewpro =
        c.command(long_cmd(cc::camera_track_point, {0.5f, 0.5f, 0, 0, 0, 0, 0}, 101), *c.find(101),
                  states(), 0);
    CHECK(viewpro.mapped.result == MavResult::unsupported);
    CHECK(viewpro.mapped.requests.empty());
}

TEST_CASE("STOP_TRACKING: hold where the camera looks") {
    CameraComponents c(cameras());
    const auto out = c.command(long_cmd(cc::camera_stop_tracking, {0, 0, 0, 0, 0, 0, 0}, 100),
                               *c.find(100), states(), 0);
    CHECK(out.track == TrackChange::stop);
    REQUIRE(out.mapped.requests.size() == 1);
    const auto& r = out.mapped.requests[0].request;
    CHECK(r["cmd"] == "rate");
    CHECK(r["pan"] == 0.0);
    CHECK(r["tilt"] == 0.0);
    CHECK(r["stabilized"] == true);
}

TEST_CASE("REQUEST_MESSAGE and the deprecated request commands: replies from the camera") {
    CameraComponents c(cameras());
    const auto cam = *c.find(100);
    const auto lookup = states(orion_with_video());
    const auto ask = [&](std::uint16_t command, std::array<float, 7> p) {
        return c.command(long_cmd(command, p, 100), cam, lookup, 42).mapped;
    };
    struct Case {
        std::uint16_t command;
        std::array<float, 7> params;
        std::uint32_t msgid;
        std::size_t replies;
    };
    const std::uint16_t rm = mav::mav_cmd::request_message;
    for (const Case& k :
         {Case{rm, {259, 0, 0, 0, 0, 0, 0}, 259, 1},
          Case{cc::request_camera_information, {1, 0, 0, 0, 0, 0, 0}, 259, 1},
          Case{rm, {260, 0, 0, 0, 0, 0, 0}, 260, 1},
          Case{cc::request_camera_settings, {1, 0, 0, 0, 0, 0, 0}, 260, 1},
          Case{rm, {261, 0, 0, 0, 0, 0, 0}, 261, 1},
          Case{cc::request_storage_information, {0, 1, 0, 0, 0, 0, 0}, 261, 1},
          Case{rm, {262, 0, 0, 0, 0, 0, 0}, 262, 1},
          Case{cc::request_camera_capture_status, {1, 0, 0, 0, 0, 0, 0}, 262, 1},
          Case{rm, {269, 0, 0, 0, 0, 0, 0}, 269, 2}, Case{rm, {269, 2, 0, 0, 0, 0, 0}, 269, 1},
          Case{cc::request_video_stream_information, {1, 0, 0, 0, 0, 0, 0}, 269, 1},
          Case{rm, {270, 1, 0, 0, 0, 0, 0}, 270, 1},
          Case{cc::request_video_stream_status, {0, 0, 0, 0, 0, 0, 0}, 270, 2},
          Case{rm, {271, 0, 0, 0, 0, 0, 0}, 271, 1}, Case{rm, {0, 0, 0, 0, 0, 0, 0}, 0, 1}}) {
        const Mapped m = ask(k.command, k.params);
        INFO("command " << k.command << " message " << k.msgid);
        CHECK(m.result == MavResult::accepted);
        CHECK(m.requests.empty());
        REQUIRE(m.replies.size() == k.replies);
        for (const auto& r : m.replies) {
            CHECK(r.component_id == 100);
            CHECK(mav::message_id(r.payload) == k.msgid);
        }
    }
    // Param 0 of a deprecated request: no action, nothing sent.
    const Mapped none = ask(cc::request_camera_information, {0, 0, 0, 0, 0, 0, 0});
    CHECK(none.result == MavResult::accepted);
    CHECK(none.replies.empty());
    // Refusals.
    CHECK(ask(rm, {269, 3, 0, 0, 0, 0, 0}).result == MavResult::denied);
    CHECK(ask(rm, {280, 0, 0, 0, 0, 0, 0}).result == MavResult::unsupported);
    CHECK(ask(rm, {-1, 0, 0, 0, 0, 0, 0}).result == MavResult::denied);
    CHECK(ask(rm, {NaN, 0, 0, 0, 0, 0, 0}).result == MavResult::denied);
    const auto no_video =
        c.command(long_cmd(rm, {269, 0, 0, 0, 0, 0, 0}, 101), *c.find(101), states(), 0);
    CHECK(no_video.mapped.result == MavResult::unsupported);
}

TEST_CASE("VIDEO_STREAM_INFORMATION and STATUS: the relayed stream and STATE video") {
    const auto cams = cameras();
    const auto info = stream_information(cams[0], 1, orion_with_video());
    CHECK(info.stream_id == 2);
    CHECK(info.count == 2);
    CHECK(info.type == mav::video_stream::type_mpeg_ts);
    CHECK(text(info.uri) == "mpegts://239.1.2.3:5600");
    CHECK(text(info.name) == "main 2");
    CHECK(info.encoding == mav::video_stream::encoding_h264);
    CHECK(info.resolution_h == 1280);
    CHECK(info.resolution_v == 720);
    CHECK(info.framerate == 30.0f);
    CHECK(info.bitrate == 4000000);
    CHECK(info.hfov == 40);
    CHECK(info.flags == mav::video_stream::flag_running);
    const auto status = stream_status(cams[0], 0, orion_state());  // no video reported yet
    CHECK(status.stream_id == 1);
    CHECK(status.flags == 0);
    CHECK(status.resolution_h == 0);
}

TEST_CASE("no storage, no capture, video mode only") {
    const auto storage = storage_information(5);
    CHECK(storage.status == mav::storage_status_not_supported);
    CHECK(storage.storage_count == 0);
    const auto capture = capture_status(5);
    CHECK(capture.image_status == 0);
    CHECK(capture.video_status == 0);
    CHECK(std::isnan(capture.available_capacity));
    CameraComponents c(cameras());
    const auto cam = *c.find(100);
    const auto run = [&](std::uint16_t command, std::array<float, 7> p) {
        return c.command(long_cmd(command, p, 100), cam, states(), 0).mapped.result;
    };
    CHECK(run(cc::set_camera_mode, {0, mav::camera_mode_video, 0, 0, 0, 0, 0}) ==
          MavResult::accepted);
    CHECK(run(cc::set_camera_mode, {0, 0, 0, 0, 0, 0, 0}) == MavResult::unsupported);
    CHECK(run(cc::image_start_capture, {0, 0, 1, 0, 0, 0, 0}) == MavResult::unsupported);
    CHECK(run(cc::video_start_capture, {0, 0, 0, 0, 0, 0, 0}) == MavResult::unsupported);
    CHECK(run(cc::camera_track_rectangle, {0.1f, 0.1f, 0.2f, 0.2f, 0, 0, 0}) ==
          MavResult::unsupported);
    CHECK(run(cc::video_start_streaming, {1, 0, 0, 0, 0, 0, 0}) == MavResult::accepted);
    CHECK(run(cc::video_start_streaming, {3, 0, 0, 0, 0, 0, 0}) == MavResult::denied);
    CHECK(run(cc::video_stop_streaming, {1, 0, 0, 0, 0, 0, 0}) == MavResult::unsupported);
    CHECK(run(cc::set_camera_focus, {1, 0, 0, 0, 0, 0, 0}) == MavResult::unsupported);
}

TEST_CASE("SET_MESSAGE_INTERVAL: the tracking status streams only") {
    CameraComponents c(cameras());
    const auto cam = *c.find(100);
    const auto set = [&](float msgid, float us) {
        return c
            .command(long_cmd(cc::set_message_interval, {msgid, us, 0, 0, 0, 0, 0}, 100), cam,
                     states(), 0)
            .mapped.result;
    };
    CHECK(c.intervals(100).image_ms == 0);
    CHECK(c.intervals(100).geo_ms == 1000);
    CHECK(set(275, 500000) == MavResult::accepted);
    CHECK(c.intervals(100).image_ms == 500);
    CHECK(set(276, 20000) == MavResult::accepted);
    CHECK(c.intervals(100).geo_ms == 100);  // at most 10 Hz
    CHECK(set(276, 0) == MavResult::accepted);
    CHECK(c.intervals(100).geo_ms == 1000);
    CHECK(set(275, -1) == MavResult::accepted);
    CHECK(c.intervals(100).image_ms == 0);
    CHECK(set(275, -5) == MavResult::denied);
    CHECK(set(275, NaN) == MavResult::denied);
    CHECK(set(33, 100000) == MavResult::unsupported);
    CHECK(c.intervals(101).geo_ms == 1000);  // per camera
}

TEST_CASE("CAMERA_TRACKING_GEO_STATUS and IMAGE_STATUS") {
    const auto idle = tracking_geo_status(std::nullopt, orion_state());
    CHECK(idle.tracking_status == mav::tracking::status_idle);
    HeldPoint p;
    p.lat = 45.01;
    p.lon = -121.0;
    p.alt = 79.0;
    p.alt_msl = 100.0;
    p.radius = 0.05f;
    const auto geo = tracking_geo_status(p, orion_state());
    CHECK(geo.tracking_status == mav::tracking::status_active);
    CHECK(geo.lat == 450100000);
    CHECK(geo.lon == -1210000000);
    CHECK(geo.alt == 100.0f);
    // From 45.0 N at 1500 m to 45.01 N at 79 m: 1111.5 m north, 1421 m down.
    CHECK(geo.dist == Approx(std::hypot(1111.5, 1421.0)).epsilon(0.005));
    CHECK(std::isnan(geo.vel_n));
    p.alt_msl.reset();
    CHECK(std::isnan(tracking_geo_status(p, orion_state()).alt));

    const auto image = tracking_image_status(p, ImageAt{0.4, -0.2});
    CHECK(image.tracking_status == mav::tracking::status_active);
    CHECK(image.tracking_mode == mav::tracking::mode_point);
    CHECK(image.point_x == Approx(0.7));
    CHECK(image.point_y == Approx(0.4));
    CHECK(image.radius == 0.05f);
    CHECK(std::isnan(tracking_image_status(p, std::nullopt).point_x));
    CHECK(tracking_image_status(std::nullopt, std::nullopt).tracking_status == 0);
}

namespace {

// The Orion's camera with video.tracking (contract section 20).
CameraComponents visual_cameras() {
    auto cams = cameras();
    cams[0].visual_tracking = true;
    return CameraComponents(cams);
}

gimbal::state::TrackState a_track() {
    gimbal::state::TrackState t;
    t.id = 7;
    t.state = "tracking";
    t.box = {-0.2, 0.1, 0.0, 0.3};
    t.centre = {-0.1, 0.2};
    t.confidence = 0.8;
    t.ground = gimbal::state::TrackGround{45.01, -121.0, 79.0};
    t.velocity = gimbal::state::TrackVelocity{3.0, 4.0, 5.0, 53.13};
    return t;
}

}  // namespace

TEST_CASE("visual tracking: TRACK_POINT and TRACK_RECTANGLE become track, flags say so") {
    auto c = visual_cameras();
    const auto cam = *c.find(100);
    namespace f = mav::camera_cap;
    CHECK(camera_component_information(cam, orion_state(), 0).flags ==
          (f::has_basic_zoom | f::has_video_stream | f::has_tracking_point |
           f::has_tracking_rectangle | f::has_tracking_geo_status));

    const auto point = c.command(
        long_cmd(cc::camera_track_point, {0.7f, 0.4f, 0.05f, 0, 0, 0, 0}, 100), cam, states(), 0);
    CHECK(point.track == TrackChange::visual);
    REQUIRE(point.mapped.requests.size() == 1);
    const auto& p = point.mapped.requests[0].request;
    CHECK(p["cmd"] == "track");
    CHECK(p["gimbal"] == "main");
    CHECK(p["x"].get<double>() == Approx(0.4).margin(1e-6));
    CHECK(p["y"].get<double>() == Approx(-0.2).margin(1e-6));
    CHECK(p["size"].get<double>() == Approx(0.1).margin(1e-6));  // twice the radius
    CHECK_FALSE(p.contains("stare"));
    // No radius: track's own default size.
    const auto bare = c.command(
        long_cmd(cc::camera_track_point, {0.5f, 0.5f, NaN, 0, 0, 0, 0}, 100), cam, states(), 0);
    REQUIRE(bare.mapped.requests.size() == 1);
    CHECK_FALSE(bare.mapped.requests[0].request.contains("size"));

    const auto rect =
        c.command(long_cmd(cc::camera_track_rectangle, {0.25f, 0.5f, 0.75f, 1.0f, 0, 0, 0}, 100),
                  cam, states(), 0);
    CHECK(rect.track == TrackChange::visual);
    REQUIRE(rect.mapped.requests.size() == 1);
    const auto& r = rect.mapped.requests[0].request;
    CHECK(r["cmd"] == "track");
    CHECK(r["x0"] == -0.5);
    CHECK(r["y0"] == 0.0);
    CHECK(r["x1"] == 0.5);
    CHECK(r["y1"] == 1.0);
}

TEST_CASE("visual tracking: refusals change nothing; without tracking a rectangle is unsupported") {
    auto c = visual_cameras();
    const auto cam = *c.find(100);
    for (const auto& p : {std::array<float, 7>{0.5f, 0.5f, 0.4f, 0.9f, 0, 0, 0},  // inverted
                          std::array<float, 7>{0.1f, 0.1f, 0.1f, 0.9f, 0, 0, 0},  // no width
                          std::array<float, 7>{0.1f, 0.1f, 1.5f, 0.9f, 0, 0, 0},
                          std::array<float, 7>{0.1f, NaN, 0.5f, 0.9f, 0, 0, 0},
                          std::array<float, 7>{0.1f, 0.1f, 0.5f, 0.9f, 101, 0, 0}}) {
        const auto out = c.command(long_cmd(cc::camera_track_rectangle, p, 100), cam, states(), 0);
        CHECK(out.mapped.result == MavResult::denied);
        CHECK(out.mapped.requests.empty());
    }
    CameraComponents plain(cameras());
    const auto out =
        plain.command(long_cmd(cc::camera_track_rectangle, {0.1f, 0.1f, 0.5f, 0.9f, 0, 0, 0}, 100),
                      *plain.find(100), states(), 0);
    CHECK(out.mapped.result == MavResult::unsupported);
    CHECK(out.mapped.requests.empty());
}

TEST_CASE("visual tracking: STOP_TRACKING stops a running track, else holds as before") {
    auto c = visual_cameras();
    auto orion = orion_state();
    orion->visual_tracking = true;
    orion->track = a_track();
    const auto stop = c.command(long_cmd(cc::camera_stop_tracking, {0, 0, 0, 0, 0, 0, 0}, 100),
                                *c.find(100), states(orion), 0);
    CHECK(stop.track == TrackChange::visual);
    REQUIRE(stop.mapped.requests.size() == 1);
    CHECK(stop.mapped.requests[0].request["cmd"] == "track_stop");
    orion->track.reset();
    const auto none = c.command(long_cmd(cc::camera_stop_tracking, {0, 0, 0, 0, 0, 0, 0}, 100),
                                *c.find(100), states(orion), 0);
    CHECK(none.track == TrackChange::stop);
    REQUIRE(none.mapped.requests.size() == 1);
    CHECK(none.mapped.requests[0].request["cmd"] == "rate");
}

TEST_CASE("visual tracking: the status messages carry STATE track") {
    auto t = a_track();
    const auto image = visual_tracking_image_status(t);
    CHECK(image.tracking_status == mav::tracking::status_active);
    CHECK(image.tracking_mode == mav::tracking::mode_rectangle);
    CHECK(image.target_data == mav::tracking::target_data_in_status);
    CHECK(image.point_x == Approx(0.45));
    CHECK(image.point_y == Approx(0.6));
    CHECK(image.rec_top_x == Approx(0.4));
    CHECK(image.rec_top_y == Approx(0.55));
    CHECK(image.rec_bottom_x == Approx(0.5));
    CHECK(image.rec_bottom_y == Approx(0.65));
    CHECK(std::isnan(image.radius));

    const auto geo = visual_tracking_geo_status(t, orion_state());
    CHECK(geo.tracking_status == mav::tracking::status_active);
    CHECK(geo.lat == 450100000);
    CHECK(geo.lon == -1210000000);
    CHECK(geo.alt == 100.0f);  // 79 m above the ellipsoid, the geoid 21 m below it
    CHECK(geo.vel_n == 3.0f);
    CHECK(geo.vel_e == 4.0f);
    CHECK(geo.hdg == Approx(53.13 * deg));
    CHECK(geo.dist == Approx(std::hypot(1111.5, 1421.0)).epsilon(0.005));

    // Lost: ERROR (not seen, coasting); not located yet: no position.
    t.state = "lost";
    t.ground.reset();
    t.velocity.reset();
    CHECK(visual_tracking_image_status(t).tracking_status == mav::tracking::status_error);
    const auto unlocated = visual_tracking_geo_status(t, orion_state());
    CHECK(unlocated.tracking_status == mav::tracking::status_error);
    CHECK(unlocated.lat == 0);
    CHECK(std::isnan(unlocated.dist));
    // None: IDLE.
    CHECK(visual_tracking_image_status(std::nullopt).tracking_status == mav::tracking::status_idle);
    CHECK(visual_tracking_geo_status(std::nullopt, orion_state()).tracking_status ==
          mav::tracking::status_idle);
}
