// JSON views in the units and names of the interface contract (section 5 `output`).
#include <catch2/catch.hpp>

#include "protocols/viewpro/codec/input.hpp"
#include "protocols/viewpro/codec/json.hpp"
#include "protocols/viewpro/codec/output.hpp"
#include "vectors.hpp"

using namespace gimbal::viewpro;
using namespace viewpro_test;
using Catch::Matchers::WithinAbs;
using nlohmann::json;

namespace {

json output_json(const Bytes& wire) {
    const auto frame = make_output_frame(wire);
    REQUIRE(frame);
    const auto out = decode_output(*frame);
    REQUIRE(out);
    return to_json(*out);
}

std::vector<std::string> keys(const json& j) {
    std::vector<std::string> k;
    for (const auto& [key, value] : j.items()) k.push_back(key);
    return k;
}

}  // namespace

TEST_CASE("OUT1 JSON has only what OUT1 carries", "[viewpro][json]") {
    const json j = output_json(icd_out1);
    CHECK(keys(j) == std::vector<std::string>{"format", "gimbal", "lrf_m", "target"});
    CHECK(j["format"] == "out1");
    CHECK(keys(j["gimbal"]) == std::vector<std::string>{"pitch", "yaw"});
    CHECK(j["gimbal"]["pitch"] == 27.0);
    CHECK(j["gimbal"]["yaw"] == 16.0);
    CHECK(j["lrf_m"] == 0.0);
    CHECK(keys(j["target"]) == std::vector<std::string>{"lat", "lon"});
    CHECK_THAT(j["target"]["lat"].get<double>(), WithinAbs(6.9428789, 1e-12));
    CHECK_THAT(j["target"]["lon"].get<double>(), WithinAbs(79.8812446, 1e-12));
}

TEST_CASE("OUT3 JSON", "[viewpro][json]") {
    const json j = output_json(golden_out3);
    CHECK(keys(j) ==
          std::vector<std::string>{"format", "gimbal", "lrf_m", "target", "time", "uav", "zoom"});
    CHECK(j["format"] == "out3");
    CHECK(j["time"] == "2022-06-30T23:59:58Z");
    CHECK(j["zoom"] == 1234);
    CHECK(keys(j["gimbal"]) == std::vector<std::string>{"pitch", "roll", "yaw"});
    CHECK_THAT(j["gimbal"]["pitch"].get<double>(), WithinAbs(-30, 1e-5));
    CHECK(keys(j["uav"]) ==
          std::vector<std::string>{"alt_msl", "lat", "lon", "pitch", "roll", "yaw"});
    CHECK_THAT(j["uav"]["yaw"].get<double>(), WithinAbs(-160, 1e-5));
    CHECK_THAT(j["uav"]["alt_msl"].get<double>(), WithinAbs(1234.567, 1e-9));
    CHECK(keys(j["target"]) == std::vector<std::string>{"lat", "lon"});
}

TEST_CASE("OUT4 JSON carries the target altitude and no UAV roll", "[viewpro][json]") {
    const json j = output_json(golden_out4);
    CHECK(j["format"] == "out4");
    CHECK(j["time"] == "2025-01-02T03:04:05Z");
    CHECK(keys(j["uav"]) == std::vector<std::string>{"alt_msl", "lat", "lon", "pitch", "yaw"});
    CHECK(keys(j["target"]) == std::vector<std::string>{"alt_msl", "lat", "lon"});
    CHECK_THAT(j["target"]["alt_msl"].get<double>(), WithinAbs(12.345, 1e-12));
    // The ADL form gives the same object.
    const auto frame = make_output_frame(golden_out4);
    REQUIRE(frame);
    const json adl = *decode_output(*frame);
    CHECK(adl == j);
}

TEST_CASE("input frames show as decoded JSON", "[viewpro][json]") {
    const json mode = to_json(*make_input_frame(hex("AA 55 0F 59 FF")));
    CHECK(mode == json{{"osd", "target"}, {"network", true}, {"serial", true}, {"format", "out3"}});
    const json shift = to_json(*make_input_frame(hex("AA 55 36 9C FF")));
    CHECK(shift["hundredths_deg"] == -100);
    CHECK(shift["deg"] == -1.0);

    const json in2 = to_json(*make_input_frame(golden_in2));
    CHECK(in2["time"] == "2024-03-15T12:34:56Z");
    CHECK_THAT(in2["yaw"].get<double>(), WithinAbs(120, 1e-5));
    CHECK_THAT(in2["lat"].get<double>(), WithinAbs(47.3977419, 1e-9));
    CHECK_THAT(in2["alt_msl"].get<double>(), WithinAbs(488.123, 1e-9));
    REQUIRE(in2["vel_ned"].size() == 3);
    CHECK_THAT(in2["vel_ned"][1].get<double>(), WithinAbs(-5.67, 1e-9));

    const json in1 = to_json(*make_input_frame(golden_in1));
    CHECK_FALSE(in1.contains("vel_ned"));

    const json in3 = to_json(*make_input_frame(golden_in3));
    CHECK_THAT(in3["lrf_m"].get<double>(), WithinAbs(1234.567, 1e-9));
    CHECK(in3["time"] == "2023-11-02T07:08:09Z");
    CHECK(in3["vel_ned"].size() == 3);
}
