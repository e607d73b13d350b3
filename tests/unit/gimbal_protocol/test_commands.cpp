// Every row of contract section 8's command table, the altitude frames, NaN/Inf parameters and
// control arbitration.
#include <catch2/catch.hpp>
#include <numbers>
#include <random>

#include "fixtures.hpp"

using namespace gptest;
namespace cmd = gimbal::mavlink::mav_cmd;
namespace frame = gimbal::mavlink::mav_frame;

TEST_CASE("gimbal device ids: configuration order, at most six") {
    const auto g = expose({{"a", "orion"},
                           {"b", "viewpro"},
                           {"c", "orion"},
                           {"d", "orion"},
                           {"e", "orion"},
                           {"f", "orion"},
                           {"g", "orion"}});
    REQUIRE(g.size() == 6);
    CHECK(g[0].device_id == 1);
    CHECK(g[5].device_id == 6);
    CHECK(g[5].name == "f");
}

TEST_CASE("one gimbal manager component per gimbal: 154, then 171..175") {
    const std::vector<std::pair<std::string, std::string>> seven = {
        {"a", "orion"}, {"b", "viewpro"}, {"c", "orion"}, {"d", "orion"},
        {"e", "orion"}, {"f", "orion"},   {"g", "orion"}};
    auto g = expose(seven);
    REQUIRE(g.size() == 6);
    const std::vector<std::uint8_t> want{154, 171, 172, 173, 174, 175};
    for (std::size_t i = 0; i < g.size(); ++i) {
        CHECK(g[i].component_id == want[i]);
        CHECK(g[i].device_id == i + 1);  // as before
    }
    // mavlink.component_id other than 154: the first takes it; 171..175 are skipped over it.
    g = expose(seven, 172);
    const std::vector<std::uint8_t> moved{172, 171, 173, 174, 175, 154};
    for (std::size_t i = 0; i < g.size(); ++i) CHECK(g[i].component_id == moved[i]);
    GimbalManager m(expose(seven, 100));
    CHECK(m.owns(100));
    CHECK(m.owns(175));
    CHECK_FALSE(m.owns(154));
    CHECK_FALSE(m.owns(0));
    CHECK(m.components() == std::vector<std::uint8_t>{100, 171, 172, 173, 174, 175});
}

TEST_CASE("a command addressed to one manager component reaches only its gimbal") {
    GimbalManager m(two_gimbals());  // main: 154, device 1; nose: 171, device 2
    const auto pitchyaw = [&](float device, std::uint8_t component) {
        return m.command(
            long_cmd(cmd::do_gimbal_manager_pitchyaw, {-10, 20, NaN, NaN, 0, 0, device}, component),
            gcs, vehicle(), states(), 0);
    };
    Mapped r = pitchyaw(0, 154);  // device 0 = every gimbal of that manager: just its own
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].gimbal == "main");
    r = pitchyaw(0, 171);
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].gimbal == "nose");
    r = pitchyaw(2, 171);
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].gimbal == "nose");
    r = pitchyaw(0, 0);  // component 0: every gimbal, as before
    CHECK(r.requests.size() == 2);
    // Another manager's device: DENIED, saying who manages it.
    r = pitchyaw(2, 154);
    CHECK(r.result == MavResult::denied);
    CHECK(r.requests.empty());
    CHECK(r.reason.find("component 171") != std::string::npos);

    // Set-point messages and control are scoped the same way.
    mav::GimbalManagerSetPitchyaw py;
    py.pitch = 0;
    py.yaw = 0;
    py.gimbal_device_id = 0;
    py.target_component = 171;
    r = m.message(py, gcs, vehicle(), states());
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].gimbal == "nose");
    mav::GimbalDeviceSetAttitude da;
    da.q = {1, 0, 0, 0};
    da.target_component = 154;
    r = m.message(da, gcs, vehicle(), states());
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].gimbal == "main");
    CHECK(m.command(long_cmd(cmd::do_gimbal_manager_configure, {-2, -2, -1, -1, 0, 0, 0}, 171), gcs,
                    vehicle(), states(), 0)
              .result == MavResult::accepted);
    CHECK(m.control(2).primary() == MavId{255, 190});
    CHECK_FALSE(m.control(1).primary());

    // REQUEST_MESSAGE to one component: only its gimbal's information, from it.
    r = m.command(long_cmd(cmd::request_message, {280, 0, 0, 0, 0, 0, 0}, 171), gcs, vehicle(),
                  states(), 0);
    REQUIRE(r.replies.size() == 1);
    CHECK(r.replies[0].component_id == 171);
    CHECK(std::get<mav::GimbalManagerInformation>(r.replies[0].payload).gimbal_device_id == 2);
    CHECK(to_string(MavResult::denied) == "MAV_RESULT_DENIED");
    CHECK(to_string(MavResult::temporarily_rejected) == "MAV_RESULT_TEMPORARILY_REJECTED");
}

TEST_CASE("DO_SET_ROI_LOCATION: Orion geopoint in every altitude frame") {
    GimbalManager m(two_gimbals());
    SECTION("COMMAND_INT GLOBAL_INT: altitude is MSL") {
        const Mapped r = m.command(int_cmd(cmd::do_set_roi_location, {1, 0, 0, 0}, 473977420,
                                           85455940, 488.5f, frame::global_int),
                                   gcs, vehicle(), states(), 0);
        REQUIRE(r.requests.size() == 1);
        const auto& q = r.requests[0].request;
        CHECK(q["cmd"] == "geopoint");
        CHECK(q["gimbal"] == "main");
        CHECK(q["lat"].get<double>() == Approx(47.397742));
        CHECK(q["lon"].get<double>() == Approx(8.545594));
        CHECK(q["alt"].get<double>() == Approx(488.5));
        CHECK(q["alt_ref"] == "msl");
    }
    SECTION("COMMAND_INT GLOBAL (0) is MSL too") {
        const Mapped r = m.command(int_cmd(cmd::do_set_roi_location, {1, 0, 0, 0}, 473977420,
                                           85455940, 488.5f, frame::global),
                                   gcs, vehicle(), states(), 0);
        REQUIRE(r.requests.size() == 1);
        CHECK(r.requests[0].request["alt"].get<double>() == Approx(488.5));
    }
    SECTION("relative frames: home MSL + altitude") {
        for (const auto f : {frame::global_relative_alt, frame::global_relative_alt_int}) {
            const Mapped r = m.command(
                int_cmd(cmd::do_set_roi_location, {1, 0, 0, 0}, 473977420, 85455940, 25, f), gcs,
                vehicle(90, 412.25), states(), 0);
            REQUIRE(r.requests.size() == 1);
            CHECK(r.requests[0].request["alt"].get<double>() == Approx(437.25));
            CHECK(r.requests[0].request["alt_ref"] == "msl");
        }
    }
    SECTION("COMMAND_LONG: degrees, altitude above home") {
        const Mapped r =
            m.command(long_cmd(cmd::do_set_roi_location, {1, 0, 0, 0, 47.5f, 8.25f, 30}), gcs,
                      vehicle(90, 400), states(), 0);
        REQUIRE(r.requests.size() == 1);
        CHECK(r.requests[0].request["lat"].get<double>() == Approx(47.5));
        CHECK(r.requests[0].request["alt"].get<double>() == Approx(430));
    }
    SECTION("relative altitude without a home: TEMPORARILY_REJECTED") {
        const Mapped r =
            m.command(long_cmd(cmd::do_set_roi_location, {1, 0, 0, 0, 47.5f, 8.25f, 30}), gcs,
                      vehicle(90, std::nullopt), states(), 0);
        CHECK(r.requests.empty());
        CHECK(r.result == MavResult::temporarily_rejected);
    }
    SECTION("terrain and other frames: UNSUPPORTED") {
        for (const std::uint8_t f : {frame::global_terrain_alt, frame::global_terrain_alt_int,
                                     std::uint8_t{1}, std::uint8_t{8}}) {
            const Mapped r = m.command(
                int_cmd(cmd::do_set_roi_location, {1, 0, 0, 0}, 473977420, 85455940, 25, f), gcs,
                vehicle(), states(), 0);
            CHECK(r.requests.empty());
            CHECK(r.result == MavResult::unsupported);
        }
    }
    SECTION("Viewpro: UNSUPPORTED; all gimbals: only the Orion") {
        const Mapped v =
            m.command(long_cmd(cmd::do_set_roi_location, {2, 0, 0, 0, 47.5f, 8.25f, 30}), gcs,
                      vehicle(), states(), 0);
        CHECK(v.requests.empty());
        CHECK(v.result == MavResult::unsupported);
        // UNSUPPORTED even when the home altitude is unknown: the protocol decides first.
        CHECK(m.command(long_cmd(cmd::do_set_roi_location, {2, 0, 0, 0, 47.5f, 8.25f, 30}), gcs,
                        vehicle(90, std::nullopt), states(), 0)
                  .result == MavResult::unsupported);
        const Mapped all =
            m.command(long_cmd(cmd::do_set_roi_location, {0, 0, 0, 0, 47.5f, 8.25f, 30}), gcs,
                      vehicle(), states(), 0);
        REQUIRE(all.requests.size() == 1);
        CHECK(all.requests[0].gimbal == "main");
    }
    SECTION("NaN, Inf, unset and out-of-range positions: DENIED") {
        for (const auto& p : {std::array<float, 7>{1, 0, 0, 0, NaN, 8, 30},
                              std::array<float, 7>{1, 0, 0, 0, 47, Inf, 30},
                              std::array<float, 7>{1, 0, 0, 0, 47, 8, NaN},
                              std::array<float, 7>{1, 0, 0, 0, 91, 8, 30},
                              std::array<float, 7>{1, 0, 0, 0, 47, -181, 30}}) {
            const Mapped r =
                m.command(long_cmd(cmd::do_set_roi_location, p), gcs, vehicle(), states(), 0);
            CHECK(r.requests.empty());
            CHECK(r.result == MavResult::denied);
        }
        const Mapped unset =
            m.command(int_cmd(cmd::do_set_roi_location, {1, 0, 0, 0},
                              std::numeric_limits<int>::max(), 0, 10, frame::global_int),
                      gcs, vehicle(), states(), 0);
        CHECK(unset.result == MavResult::denied);
    }
    SECTION("unknown gimbal device id: DENIED") {
        const Mapped r =
            m.command(long_cmd(cmd::do_set_roi_location, {7, 0, 0, 0, 47.5f, 8.25f, 30}), gcs,
                      vehicle(), states(), 0);
        CHECK(r.result == MavResult::denied);
        CHECK(r.requests.empty());
    }
}

TEST_CASE("DO_SET_ROI_NONE: Orion rate 0, 0 stabilized") {
    GimbalManager m(two_gimbals());
    const Mapped r = m.command(long_cmd(cmd::do_set_roi_none, {0, 0, 0, 0, 0, 0, 0}), gcs,
                               vehicle(), states(), 0);
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].request == nlohmann::json{{"cmd", "rate"},
                                                  {"gimbal", "main"},
                                                  {"pan", 0.0},
                                                  {"tilt", 0.0},
                                                  {"stabilized", true}});
    const Mapped v = m.command(long_cmd(cmd::do_set_roi_none, {2, 0, 0, 0, 0, 0, 0}), gcs,
                               vehicle(), states(), 0);
    CHECK(v.result == MavResult::unsupported);
}

TEST_CASE("DO_GIMBAL_MANAGER_PITCHYAW: angles, rates, earth frame, Viewpro steps") {
    GimbalManager m(two_gimbals());
    SECTION("angles: Orion position, pitch = tilt, yaw = pan") {
        const Mapped r =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-30, 45, NaN, NaN, 0, 0, 1}), gcs,
                      vehicle(), states(), 0);
        REQUIRE(r.requests.size() == 1);
        CHECK(r.requests[0].request ==
              nlohmann::json{
                  {"cmd", "position"}, {"gimbal", "main"}, {"pan", 45.0}, {"tilt", -30.0}});
    }
    SECTION("rates with NaN angles: Orion rate") {
        const Mapped r =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {NaN, NaN, 5, -10, 0, 0, 1}), gcs,
                      vehicle(), states(), 0);
        REQUIRE(r.requests.size() == 1);
        CHECK(r.requests[0].request ==
              nlohmann::json{{"cmd", "rate"}, {"gimbal", "main"}, {"pan", -10.0}, {"tilt", 5.0}});
    }
    SECTION("YAW_LOCK / YAW_IN_EARTH_FRAME: yaw from north minus the heading") {
        for (const float flags : {16.0f, 64.0f}) {
            const Mapped r = m.command(
                long_cmd(cmd::do_gimbal_manager_pitchyaw, {-10, 30, NaN, NaN, flags, 0, 1}), gcs,
                vehicle(350), states(), 0);
            REQUIRE(r.requests.size() == 1);
            CHECK(r.requests[0].request["pan"].get<double>() == Approx(40));
        }
        const Mapped no_heading =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-10, 30, NaN, NaN, 16, 0, 1}), gcs,
                      vehicle(std::nullopt), states(), 0);
        CHECK(no_heading.result == MavResult::temporarily_rejected);
        CHECK(no_heading.requests.empty());
    }
    SECTION("one angle NaN: the other axis keeps its reported angle") {
        const Mapped r =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-50, NaN, NaN, NaN, 0, 0, 1}), gcs,
                      vehicle(), states(), 0);
        REQUIRE(r.requests.size() == 1);
        CHECK(r.requests[0].request["pan"].get<double>() == Approx(30));
        CHECK(r.requests[0].request["tilt"].get<double>() == Approx(-50));
    }
    SECTION("all NaN, or any Inf: DENIED, nothing sent") {
        for (const auto& p : {std::array<float, 7>{NaN, NaN, NaN, NaN, 0, 0, 1},
                              std::array<float, 7>{Inf, 0, NaN, NaN, 0, 0, 1},
                              std::array<float, 7>{NaN, NaN, -Inf, 0, 0, 0, 1}}) {
            const Mapped r = m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, p), gcs, vehicle(),
                                       states(), 0);
            CHECK(r.result == MavResult::denied);
            CHECK(r.requests.empty());
        }
    }
    SECTION("Viewpro: angles as adjust steps from its reported angles, at most 20 degrees") {
        const Mapped r =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-50, 15, NaN, NaN, 0, 0, 2}), gcs,
                      vehicle(), states(), 0);
        REQUIRE(r.requests.size() == 1);
        CHECK(r.requests[0].request == nlohmann::json{{"cmd", "viewpro_adjust"},
                                                      {"gimbal", "nose"},
                                                      {"yaw_deg", 5.0},
                                                      {"pitch_deg", -5.0}});
        const Mapped far =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-90, 10, NaN, NaN, 0, 0, 2}), gcs,
                      vehicle(), states(), 0);
        REQUIRE(far.requests.size() == 1);
        CHECK(far.requests[0].request["pitch_deg"].get<double>() == Approx(-20));
        CHECK_FALSE(far.requests[0].request.contains("yaw_deg"));
    }
    SECTION("Viewpro rates: UNSUPPORTED; no angles yet: TEMPORARILY_REJECTED") {
        const Mapped r =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {NaN, NaN, 5, 5, 0, 0, 2}), gcs,
                      vehicle(), states(), 0);
        CHECK(r.result == MavResult::unsupported);
        const Mapped none =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-10, 0, NaN, NaN, 0, 0, 2}), gcs,
                      vehicle(), states(orion_state(), empty_viewpro()), 0);
        CHECK(none.result == MavResult::temporarily_rejected);
    }
    SECTION("device id 0: every gimbal") {
        const Mapped r =
            m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-30, 20, NaN, NaN, 0, 0, 0}), gcs,
                      vehicle(), states(), 0);
        REQUIRE(r.requests.size() == 2);
        CHECK(r.requests[0].gimbal == "main");
        CHECK(r.requests[1].gimbal == "nose");
    }
}

TEST_CASE("GIMBAL_MANAGER_SET_PITCHYAW, SET_ATTITUDE and GIMBAL_DEVICE_SET_ATTITUDE") {
    GimbalManager m(two_gimbals());
    mav::GimbalManagerSetPitchyaw py;
    py.pitch = static_cast<float>(-30 * M_PI / 180);
    py.yaw = static_cast<float>(45 * M_PI / 180);
    py.gimbal_device_id = 1;
    Mapped r = m.message(py, gcs, vehicle(), states());
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].request["cmd"] == "position");
    CHECK(r.requests[0].request["pan"].get<double>() == Approx(45).margin(1e-4));
    CHECK(r.requests[0].request["tilt"].get<double>() == Approx(-30).margin(1e-4));

    py.pitch = NaN;
    py.yaw = NaN;
    py.pitch_rate = static_cast<float>(10 * M_PI / 180);
    py.yaw_rate = 0;
    r = m.message(py, gcs, vehicle(), states());
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].request["cmd"] == "rate");
    CHECK(r.requests[0].request["tilt"].get<double>() == Approx(10).margin(1e-4));

    const auto q = gimbal::geo::euler_to_quat(gimbal::geo::EulerDeg{0, -25, 60});
    mav::GimbalManagerSetAttitude sa;
    sa.q = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
            static_cast<float>(q.z)};
    sa.gimbal_device_id = 1;
    r = m.message(sa, gcs, vehicle(), states());
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].request["pan"].get<double>() == Approx(60).margin(1e-3));
    CHECK(r.requests[0].request["tilt"].get<double>() == Approx(-25).margin(1e-3));

    mav::GimbalDeviceSetAttitude da;
    da.q = sa.q;
    r = m.message(da, gcs, vehicle(), states());
    REQUIRE(r.requests.size() == 2);  // the same as SET_ATTITUDE, for every gimbal
    CHECK(r.requests[0].request["cmd"] == "position");

    mav::GimbalDeviceSetAttitude rates;
    rates.q = {NaN, NaN, NaN, NaN};
    rates.angular_velocity_y = 0.1f;
    rates.angular_velocity_z = 0.2f;
    r = m.message(rates, gcs, vehicle(), states());
    REQUIRE(r.requests.size() == 1);  // Viewpro takes no rates: only the Orion
    CHECK(r.requests[0].request["cmd"] == "rate");

    mav::GimbalManagerSetAttitude nothing;
    nothing.q = {NaN, NaN, NaN, NaN};
    r = m.message(nothing, gcs, vehicle(), states());
    CHECK(r.result == MavResult::denied);
    CHECK(r.requests.empty());
}

TEST_CASE("DO_GIMBAL_MANAGER_CONFIGURE: arbitration as common.xml defines it") {
    GimbalManager m(two_gimbals());
    const auto configure = [&](const MavId& who, float p1, float p2, float p3, float p4,
                               float device = 0) {
        return m.command(long_cmd(cmd::do_gimbal_manager_configure, {p1, p2, p3, p4, 0, 0, device}),
                         who, vehicle(), states(), 0);
    };
    const auto steer = [&](const MavId& who) {
        return m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-10, 0, NaN, NaN, 0, 0, 1}),
                         who, vehicle(), states(), 0);
    };
    CHECK(steer(other_gcs).requests.size() == 1);  // no primary: anyone steers

    CHECK(configure(gcs, -2, -2, -1, -1).result == MavResult::accepted);  // take control
    CHECK(m.control(1).primary() == MavId{255, 190});
    CHECK(m.control(2).primary() == MavId{255, 190});
    CHECK(steer(gcs).requests.size() == 1);
    const Mapped refused = steer(other_gcs);
    CHECK(refused.result == MavResult::denied);
    CHECK(refused.requests.empty());
    CHECK(m.denied() == 1);
    // ROI and SET_PITCHYAW from the other GCS are refused as well.
    CHECK(m.command(long_cmd(cmd::do_set_roi_location, {0, 0, 0, 0, 47, 8, 10}), other_gcs,
                    vehicle(), states(), 0)
              .result == MavResult::denied);
    mav::GimbalManagerSetPitchyaw py;
    py.pitch = 0;
    py.yaw = 0;
    CHECK(m.message(py, other_gcs, vehicle(), states()).result == MavResult::denied);

    // A secondary may steer too.
    CHECK(configure(gcs, -1, -1, 254, 190).result == MavResult::accepted);
    CHECK(steer(other_gcs).requests.size() == 1);
    // -3 from someone not in control changes nothing; from the primary releases.
    CHECK(configure(MavId{9, 9}, -3, -3, -1, -1).result == MavResult::accepted);
    CHECK(m.control(1).primary() == MavId{255, 190});
    CHECK(configure(gcs, -3, -3, 0, 0).result == MavResult::accepted);
    CHECK_FALSE(m.control(1).primary());
    CHECK_FALSE(m.control(1).secondary());
    // An explicit id, for one gimbal only.
    CHECK(configure(gcs, 1, 1, -1, -1, 2).result == MavResult::accepted);
    CHECK(m.control(2).primary() == MavId{1, 1});
    CHECK_FALSE(m.control(1).primary());
    // 0: no one.
    CHECK(configure(gcs, 0, 0, -1, -1, 2).result == MavResult::accepted);
    CHECK_FALSE(m.control(2).primary());
    // Invalid values: DENIED, nothing changed.
    for (const auto& bad :
         {std::array<float, 4>{1.5f, 1, -1, -1}, std::array<float, 4>{Inf, 0, -1, -1},
          std::array<float, 4>{256, 1, -1, -1}, std::array<float, 4>{-4, -4, -1, -1},
          std::array<float, 4>{5, -2, -1, -1}}) {
        CHECK(configure(gcs, bad[0], bad[1], bad[2], bad[3]).result == MavResult::denied);
        CHECK_FALSE(m.control(1).primary());
    }
    // NaN leaves a slot unchanged.
    CHECK(configure(gcs, -2, -2, NaN, NaN).result == MavResult::accepted);
    CHECK(m.control(1).primary() == MavId{255, 190});
    CHECK(configure(gcs, 1, 1, -1, -1, 9).result == MavResult::denied);  // no gimbal 9
}

TEST_CASE("SET_CAMERA_ZOOM: range and continuous -> Orion camera_zoom") {
    GimbalManager m(two_gimbals());
    const auto zoom = [&](float type, float value, float camera = 1, StateLookup s = states()) {
        return m.command(long_cmd(cmd::set_camera_zoom, {type, value, camera, 0, 0, 0, 0}), gcs,
                         vehicle(), s, 0);
    };
    // 129 / 4.3 = 30x optical range.
    Mapped r = zoom(2, 50);
    REQUIRE(r.requests.size() == 1);
    CHECK(r.requests[0].request ==
          nlohmann::json{{"cmd", "camera_zoom"}, {"gimbal", "main"}, {"zoom", 15.5}});
    CHECK(zoom(2, 0).requests[0].request["zoom"].get<double>() == Approx(1));
    CHECK(zoom(2, 100).requests[0].request["zoom"].get<double>() == Approx(30));
    CHECK(zoom(1, 1).requests[0].request["zoom"].get<double>() == Approx(30));
    CHECK(zoom(1, -0.5f).requests[0].request["zoom"].get<double>() == Approx(1));
    const Mapped stop = zoom(1, 0);
    CHECK(stop.requests.empty());
    CHECK(stop.result == MavResult::accepted);
    CHECK(zoom(2, 101).result == MavResult::denied);
    CHECK(zoom(2, NaN).result == MavResult::denied);
    CHECK(zoom(1, 2).result == MavResult::denied);
    CHECK(zoom(0, 1).result == MavResult::unsupported);      // step
    CHECK(zoom(4, 30).result == MavResult::unsupported);     // horizontal fov
    CHECK(zoom(2, 50, 2).result == MavResult::unsupported);  // Viewpro
    CHECK(zoom(2, 50, 9).result == MavResult::denied);
    auto no_cameras = orion_state();
    no_cameras->data.packets.cameras.reset();
    CHECK(zoom(2, 50, 1, states(no_cameras)).result == MavResult::temporarily_rejected);
}

TEST_CASE("REQUEST_MESSAGE: information messages per gimbal") {
    GimbalManager m(two_gimbals());
    const auto request = [&](float id, float index = 0) {
        return m.command(long_cmd(cmd::request_message, {id, index, 0, 0, 0, 0, 0}), gcs, vehicle(),
                         states(), 1234);
    };
    Mapped r = request(280);
    CHECK(r.result == MavResult::accepted);
    REQUIRE(r.replies.size() == 2);
    const auto& info = std::get<mav::GimbalManagerInformation>(r.replies[0].payload);
    CHECK(info.gimbal_device_id == 1);
    CHECK(info.time_boot_ms == 1234);
    CHECK(info.pitch_min == Approx(-120 * M_PI / 180));
    CHECK(info.pitch_max == Approx(30 * M_PI / 180));
    CHECK(info.yaw_max == Approx(M_PI));
    CHECK((info.cap_flags & mav::gimbal_cap::can_point_location_global) != 0);
    CHECK(std::get<mav::GimbalManagerInformation>(r.replies[1].payload).gimbal_device_id == 2);
    // Each from its gimbal's own manager component.
    CHECK(r.replies[0].component_id == 154);
    CHECK(r.replies[1].component_id == 171);

    r = request(283, 2);
    REQUIRE(r.replies.size() == 1);
    const auto& dev = std::get<mav::GimbalDeviceInformation>(r.replies[0].payload);
    CHECK(dev.gimbal_device_id == 2);
    CHECK(std::string(reinterpret_cast<const char*>(dev.custom_name.data())) == "nose");

    r = request(259, 1);
    REQUIRE(r.replies.size() == 1);
    const auto& cam = std::get<mav::CameraInformation>(r.replies[0].payload);
    CHECK(cam.resolution_h == 1920);
    CHECK((cam.flags & mav::camera_cap_has_basic_zoom) != 0);

    CHECK(request(33).result == MavResult::unsupported);
    CHECK(request(NaN).result == MavResult::denied);
    CHECK(request(-1).result == MavResult::denied);
    CHECK(request(280, 8).result == MavResult::denied);
}

TEST_CASE("a manager whose gimbal has a camera component leaves CAMERA_INFORMATION to it") {
    // Contract v4 (section 8): MAVSDK's Camera plugin listed every camera twice, [154, 100].
    auto gimbals = two_gimbals();
    gimbals[0].camera_component = 100;  // main has a camera component, nose has none
    GimbalManager m(gimbals);
    const auto request = [&](std::uint8_t component, float device) {
        auto c = long_cmd(cmd::request_message, {259, device, 0, 0, 0, 0, 0});
        c.target_component = component;
        return m.command(c, gcs, vehicle(), states(), 0);
    };
    Mapped r = request(154, 0);
    CHECK(r.result == MavResult::denied);  // the command is known; this message is not ours
    CHECK(r.replies.empty());
    CHECK(r.reason.find("camera component: 100 (main)") != std::string::npos);
    // The broadcast: only the gimbal without a camera component answers, from its manager.
    r = request(0, 0);
    CHECK(r.result == MavResult::accepted);
    REQUIRE(r.replies.size() == 1);
    CHECK(r.replies[0].component_id == 171);
    CHECK(std::holds_alternative<mav::CameraInformation>(r.replies[0].payload));
    CHECK(request(0, 1).result == MavResult::denied);
    // Every other message is still the manager's.
    auto info = long_cmd(cmd::request_message, {280, 0, 0, 0, 0, 0, 0});
    CHECK(m.command(info, gcs, vehicle(), states(), 0).replies.size() == 2);
}

TEST_CASE("unknown commands: UNSUPPORTED; nothing maps to the laser") {
    GimbalManager m(two_gimbals());
    for (const std::uint16_t c : {std::uint16_t{400}, std::uint16_t{203}, std::uint16_t{2000},
                                  std::uint16_t{205}, std::uint16_t{0}}) {
        const Mapped r = m.command(long_cmd(c, {1, 1, 1, 1, 1, 1, 1}), gcs, vehicle(), states(), 0);
        CHECK(r.result == MavResult::unsupported);
        CHECK(r.requests.empty());
    }
    // Random parameters for every handled command never produce a laser request.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> any(-400, 400);
    for (int i = 0; i < 2000; ++i) {
        for (const std::uint16_t c :
             {cmd::do_set_roi_location, cmd::do_set_roi_none, cmd::do_gimbal_manager_pitchyaw,
              cmd::set_camera_zoom, cmd::do_gimbal_manager_configure, cmd::request_message}) {
            std::array<float, 7> p{};
            for (float& v : p) v = (rng() % 5 == 0) ? NaN : any(rng);
            CHECK(no_laser(m.command(long_cmd(c, p), gcs, vehicle(), states(), 0)));
        }
    }
}

TEST_CASE("gimbald error codes -> MAV_RESULT") {
    CHECK(result_for_error("link_down") == MavResult::temporarily_rejected);
    CHECK(result_for_error("unavailable") == MavResult::temporarily_rejected);
    CHECK(result_for_error("unsupported") == MavResult::unsupported);
    CHECK(result_for_error("out_of_range") == MavResult::denied);
    CHECK(result_for_error("bad_request") == MavResult::denied);
    CHECK(result_for_error("forbidden") == MavResult::denied);
    CHECK(result_for_error("internal") == MavResult::failed);
    CHECK(combine({MavResult::unsupported, MavResult::accepted}) == MavResult::accepted);
    CHECK(combine({MavResult::temporarily_rejected, MavResult::denied}) ==
          MavResult::temporarily_rejected);
}

TEST_CASE("gimbald error codes -> MAV_RESULT, every code as the enum and its spelling") {
    using gimbal::command::ErrorCode;
    for (std::size_t i = 0; i < gimbal::command::error_code_names.size(); ++i) {
        const auto code = static_cast<ErrorCode>(i);
        INFO(gimbal::command::to_string(code));
        CHECK(result_for_error(code) == result_for_error(gimbal::command::to_string(code)));
    }
    CHECK(result_for_error(ErrorCode::rate_limited) == MavResult::temporarily_rejected);
    CHECK(result_for_error(ErrorCode::busy) == MavResult::failed);
    CHECK(result_for_error("not_a_code") == MavResult::failed);
}

TEST_CASE("a MAVLink gimbal device is steered and reported through its capabilities") {
    GimbalManager m(expose({{"gremsy", "mavlink"}}));
    const auto device = device_state();
    const StateLookup state = [device](const std::string&) { return device->view(); };

    // PITCHYAW angles: a position (yaw from north converted with the heading), rates: a rate.
    auto out =
        m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw,
                           {-10, 120, NaN, NaN, mav::gimbal_flags::yaw_in_earth_frame, 0, 0}),
                  gcs, vehicle(90.0), state, 0);
    REQUIRE(out.requests.size() == 1);
    CHECK(
        out.requests[0].request ==
        nlohmann::json{{"cmd", "position"}, {"gimbal", "gremsy"}, {"pan", 30.0}, {"tilt", -10.0}});
    out = m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {NaN, NaN, 5, -3, 0, 0, 0}), gcs,
                    vehicle(), state, 0);
    REQUIRE(out.requests.size() == 1);
    CHECK(out.requests[0].request["cmd"] == "rate");
    CHECK(out.requests[0].request["pan"] == -3.0);
    // A left-out angle keeps the device's current one.
    out = m.command(long_cmd(cmd::do_gimbal_manager_pitchyaw, {-5, NaN, NaN, NaN, 0, 0, 0}), gcs,
                    vehicle(), state, 0);
    REQUIRE(out.requests.size() == 1);
    CHECK(out.requests[0].request["pan"] == 15.0);

    // ROI location: a geopoint; ROI none: rate 0 (no Orion-only "stabilized" key).
    out = m.command(int_cmd(cmd::do_set_roi_location, {0, 0, 0, 0}, 457000000, -1215000000, 300,
                            mav::mav_frame::global_int),
                    gcs, vehicle(), state, 0);
    REQUIRE(out.requests.size() == 1);
    CHECK(out.requests[0].request["cmd"] == "geopoint");
    out =
        m.command(long_cmd(cmd::do_set_roi_none, {0, 0, 0, 0, 0, 0, 0}), gcs, vehicle(), state, 0);
    REQUIRE(out.requests.size() == 1);
    CHECK(out.requests[0].request ==
          nlohmann::json{{"cmd", "rate"}, {"gimbal", "gremsy"}, {"pan", 0.0}, {"tilt", 0.0}});

    // No zoom on a gimbal device: its camera is another component.
    out = m.command(long_cmd(cmd::set_camera_zoom, {mav::zoom_type::range, 50, 0, 0, 0, 0, 0}), gcs,
                    vehicle(), state, 0);
    CHECK(out.requests.empty());
    CHECK(out.result == MavResult::unsupported);

    // Status: its attitude, its limits, its capability flags, its field of view.
    const auto& g = m.gimbals()[0];
    const auto att = attitude_status(g, device_state(), 0);
    const auto e =
        gimbal::geo::quat_to_euler(gimbal::geo::Quat{att.q[0], att.q[1], att.q[2], att.q[3]});
    CHECK(e.pitch_deg == Approx(-30).margin(1e-3));
    CHECK(e.yaw_deg == Approx(105).margin(1e-3));  // 15 from the nose, heading 90
    const auto info = manager_information(g, device_state(), 0);
    CHECK(info.pitch_min == Approx(-120 * std::numbers::pi / 180));
    CHECK(info.yaw_max == Approx(170 * std::numbers::pi / 180));
    namespace c = mav::gimbal_cap;
    CHECK((info.cap_flags & c::can_point_location_global) != 0);
    CHECK((info.cap_flags & c::supports_yaw_in_earth_frame) != 0);
    CHECK((info.cap_flags & c::supports_infinite_yaw) == 0);
    const auto fov = fov_status(g, device_state(), 0);
    CHECK(fov.lat_camera == 457000000);
    CHECK(fov.alt_image == 100000);  // 79 m above the ellipsoid, geoid -21 m: 100 m MSL
    CHECK(fov.hfov == Approx(60));
}
