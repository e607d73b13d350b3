#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "orion/json.hpp"
#include "orion/packets.hpp"

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
