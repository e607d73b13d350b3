// `geopoint` for a gimbal gimbald aims itself (a MAVLink device, a SIYI camera): read once,
// with the catalogue's ranges, the same refusals for both.
#include <catch2/catch.hpp>

#include "command/geopoint_request.hpp"

using namespace gimbal;
using nlohmann::json;

namespace {

command::Result<command::AimedGeopoint> read(const json& request, double geoid = 20.0) {
    command::JsonParams p(request, "geopoint");
    return command::read_aimed_geopoint(p, geoid, "a test gimbal");
}

}  // namespace

TEST_CASE("aimed geopoint: the point above the ellipsoid, its velocity and stare") {
    auto g = read({{"lat", 45.7},
                   {"lon", -121.5},
                   {"alt", 100},
                   {"vel_ned", {1, -2, 0.5}},
                   {"stare", true},
                   {"closure", true}});
    REQUIRE(g);
    CHECK(g->point.lat_deg == 45.7);
    CHECK(g->point.lon_deg == -121.5);
    CHECK(g->point.alt_m == 100);  // wgs84 by default
    CHECK(g->vel_ned == std::array<double, 3>{1, -2, 0.5});
    CHECK(g->stare);

    g = read({{"lat", 45.7}, {"lon", -121.5}, {"alt", 100}, {"alt_ref", "msl"}});
    REQUIRE(g);
    CHECK(g->point.alt_m == Approx(120));  // plus the geoid's undulation
    CHECK(g->vel_ned == std::array<double, 3>{0, 0, 0});
    CHECK_FALSE(g->stare);
}

TEST_CASE("aimed geopoint: refusals name the key or the reason") {
    const auto code_of = [](const command::Result<command::AimedGeopoint>& r) {
        REQUIRE_FALSE(r);
        return r.error().code;
    };
    CHECK(code_of(read({{"lat", 91}, {"lon", 0}, {"alt", 0}})) == command::ErrorCode::out_of_range);
    CHECK(code_of(read({{"lon", 0}, {"alt", 0}})) == command::ErrorCode::bad_request);
    CHECK(code_of(read({{"lat", 0}, {"lon", 0}, {"alt", 0}, {"speed", 3}})) ==
          command::ErrorCode::bad_request);
    const auto joystick = read({{"lat", 0}, {"lon", 0}, {"alt", 0}, {"joystick_range_m", 500}});
    CHECK(code_of(joystick) == command::ErrorCode::bad_request);
    CHECK_THAT(joystick.error().message, Catch::Contains("a test gimbal"));
    CHECK(code_of(read({{"lat", 0}, {"lon", 0}, {"alt", 0}, {"alt_ref", "terrain"}})) ==
          command::ErrorCode::unavailable);
}
