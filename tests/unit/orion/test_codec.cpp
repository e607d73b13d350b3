#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "protocols/orion/codec/json.hpp"
#include "protocols/orion/codec/packets.hpp"

using namespace gimbal::orion;
using Bytes = std::vector<std::uint8_t>;

TEST_CASE("GeopointCmd encodes degrees as radians x 180e7/pi", "[orion][codec]") {
    GeopointCmd cmd;
    JsonError err;
    REQUIRE(from_json(
        nlohmann::json{{"lat", 45.7}, {"lon", -121.5}, {"alt", 300.0}, {"options", "stare"}}, cmd,
        err));
    const Payload p = encode(cmd);
    REQUIRE(p.size == 21);
    // 45.7 deg -> 457000000 = 0x1B3D4440
    CHECK(Bytes(p.bytes.begin(), p.bytes.begin() + 4) == Bytes{0x1B, 0x3D, 0x44, 0x40});
    auto back = decode<GeopointCmd>(p.view());
    REQUIRE(back.ok);
    CHECK(to_json(back.value)["lat"].get<double>() == Approx(45.7));
    CHECK(to_json(back.value)["options"] == "stare");
}

TEST_CASE("a fixed repeat of structures reads back from its own JSON", "[orion][codec]") {
    Vibration v;
    REQUIRE(v.fft_data.size() == 16);
    v.fft_data[3].frequency = 50.0;
    const nlohmann::json j = to_json(v);
    Vibration back;
    JsonError err;
    REQUIRE(from_json(j, back, err));
    CHECK(back.fft_data.size() == 16);
    CHECK(back.fft_data[3].frequency == Approx(50.0));
    nlohmann::json short_list = j;
    short_list["fft_data"].erase(0);
    CHECK_FALSE(from_json(short_list, back, err));
    CHECK(err.code == "bad_request");
    CHECK_THAT(err.message, Catch::Contains("exactly 16"));
}

TEST_CASE("wire text keeps printable ASCII only, so its JSON reads back", "[orion][codec]") {
    CHECK(printable(std::string("ok\tline\n\x01\xC3\xA9.", 12)) == "ok?line????.");
    DebugString d;
    d.description = "line one\nline two";
    const nlohmann::json j = to_json(d);
    CHECK(j["description"] == "line one?line two");
    DebugString back;
    JsonError err;
    CHECK(from_json(j, back, err));
}
