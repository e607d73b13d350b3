// Viewpro commands of contract section 4.3: parameters -> exact frames.
#include <catch2/catch.hpp>

#include "protocols/viewpro/codec/input.hpp"
#include "protocols/viewpro/viewpro_commands.hpp"

using namespace gimbal;
using nlohmann::json;
using Bytes = std::vector<std::uint8_t>;

namespace {

struct Planned {
    std::optional<command::Error> error;
    command::Plan plan;
};

Planned plan(const std::string& cmd, json request, double unix_s = 0) {
    Planned p;
    p.error = command::plan_viewpro(cmd, request, command::ViewproContext{unix_s}, p.plan);
    return p;
}

void require_error(const Planned& p, const std::string& code, const std::string& mentions) {
    REQUIRE(p.error);
    CHECK(p.error->code == code);
    CHECK_THAT(p.error->message, Catch::Contains(mentions));
    CHECK(p.plan.packets.empty());
}

}  // namespace

TEST_CASE("viewpro_output encodes the mode byte from its bit fields", "[command][viewpro]") {
    // ICD example 1.2: target on OSD, serial and RJ45, OUT3 -> AA 55 0F 59 FF.
    auto p = plan("viewpro_output",
                  {{"osd", "target"}, {"serial", true}, {"network", true}, {"format", "out3"}});
    REQUIRE_FALSE(p.error);
    REQUIRE(p.plan.packets.size() == 1);
    CHECK(p.plan.packets[0].frame == Bytes{0xAA, 0x55, 0x0F, 0x59, 0xFF});
    CHECK(p.plan.packets[0].sent == json{{"frame", "mode"}, {"len", 5}});
    // ICD example 1.3: UAV on OSD, serial, OUT2 -> AA 55 0F 30 FF.
    p = plan("viewpro_output",
             {{"osd", "uav"}, {"serial", true}, {"network", false}, {"format", "out2"}});
    REQUIRE_FALSE(p.error);
    CHECK(p.plan.packets[0].frame == Bytes{0xAA, 0x55, 0x0F, 0x30, 0xFF});

    require_error(
        plan("viewpro_output",
             {{"osd", "target"}, {"serial", true}, {"network", true}, {"format", "out5"}}),
        "bad_request", "format");
    require_error(plan("viewpro_output", {{"osd", "target"}, {"serial", true}, {"format", "out1"}}),
                  "bad_request", "network");
}

TEST_CASE("viewpro_adjust splits shifts into steps of at most one degree, yaw first",
          "[command][viewpro]") {
    // ICD section 5.2: 5.5 degrees up = five 0x64 steps and one 0x32.
    auto p = plan("viewpro_adjust", {{"pitch_deg", 5.5}, {"yaw_deg", -1.0}});
    REQUIRE_FALSE(p.error);
    REQUIRE(p.plan.packets.size() == 7);
    CHECK(p.plan.packets[0].frame == Bytes{0xAA, 0x55, 0x06, 0x9C, 0xFF});  // yaw -1.00
    CHECK(p.plan.packets[0].sent == json{{"frame", "yaw_shift"}, {"len", 5}});
    for (int i = 1; i <= 5; ++i)
        CHECK(p.plan.packets[static_cast<std::size_t>(i)].frame ==
              Bytes{0xAA, 0x55, 0x36, 0x64, 0xFF});
    CHECK(p.plan.packets[6].frame == Bytes{0xAA, 0x55, 0x36, 0x32, 0xFF});
    CHECK(p.plan.result["steps"] == 7);

    p = plan("viewpro_adjust", {{"yaw_deg", 0.01}});
    REQUIRE_FALSE(p.error);
    REQUIRE(p.plan.packets.size() == 1);
    CHECK(p.plan.packets[0].frame == Bytes{0xAA, 0x55, 0x06, 0x01, 0xFF});

    require_error(plan("viewpro_adjust", json::object()), "bad_request", "yaw_deg");
    require_error(plan("viewpro_adjust", {{"yaw_deg", 20.5}}), "out_of_range", "yaw_deg");
    require_error(plan("viewpro_adjust", {{"roll_deg", 1}}), "bad_request", "roll_deg");
}

TEST_CASE("vehicle sends IN2 with vel_ned, IN1 without", "[command][viewpro]") {
    const json base{{"time", "2026-11-21T06:41:50Z"},
                    {"roll", 1.5},
                    {"pitch", -2.0},
                    {"yaw", 90.0},
                    {"lat", 45.7},
                    {"lon", -121.5},
                    {"alt_msl", 1500.0}};
    auto p = plan("vehicle", base);
    REQUIRE_FALSE(p.error);
    REQUIRE(p.plan.packets.size() == 1);
    CHECK(p.plan.packets[0].sent == json{{"frame", "in1"}, {"len", 34}});
    auto frame = viewpro::make_input_frame(p.plan.packets[0].frame);
    REQUIRE(frame);
    auto in = viewpro::decode_vehicle(*frame);
    REQUIRE(in);
    CHECK(in->time == viewpro::DateTime{2026, 11, 21, 6, 41, 50});
    CHECK(in->yaw_deg == Approx(90.0).margin(1e-4));
    CHECK(in->lat_deg == Approx(45.7).margin(1e-7));
    CHECK(in->alt_msl_m == Approx(1500.0).margin(0.001));
    CHECK_FALSE(in->vel_ned_mps);

    json with_vel = base;
    with_vel["vel_ned"] = {1.0, -2.5, 0.25};
    with_vel.erase("time");
    p = plan("vehicle", with_vel, 1795761710.0);  // 2026-11-27T06:41:50Z
    REQUIRE_FALSE(p.error);
    CHECK(p.plan.packets[0].sent == json{{"frame", "in2"}, {"len", 40}});
    frame = viewpro::make_input_frame(p.plan.packets[0].frame);
    REQUIRE(frame);
    in = viewpro::decode_vehicle(*frame);
    REQUIRE(in);
    REQUIRE(in->vel_ned_mps);
    CHECK((*in->vel_ned_mps)[1] == Approx(-2.5));
    CHECK(in->time.year == 2026);
    CHECK(in->time.hour == 6);

    json bad = base;
    bad["time"] = "yesterday";
    require_error(plan("vehicle", bad), "bad_request", "time");
    bad = base;
    bad.erase("lat");
    require_error(plan("vehicle", bad), "bad_request", "lat");
    bad = base;
    bad["pitch"] = 95;
    require_error(plan("vehicle", bad), "out_of_range", "pitch");
}
