// Altitudes left to the terrain in geopoint and path (session/ground_altitude.hpp): filled
// in from the surface, heights above ground added, every refusal clear and naming its key.
#include <catch2/catch.hpp>

#include "geo/sampled_surface.hpp"
#include "session/ground_altitude.hpp"

using namespace gimbal;
using command::ErrorCode;
using nlohmann::json;

namespace {

// 400 m plus 1 m per 0.001 degree of latitude north of 45.7, over 45.6..45.8 N,
// 121.6..121.4 W (nodes on a 0.001-degree lattice, so bilinear is exact).
geo::SampledSurface slope() {
    return geo::SampledSurface([](double lat, double) { return 400.0 + (lat - 45.7) * 1000; },
                               geo::Lattice{0, 0, 0.001, 0.001}, 600.0,
                               geo::GeoRect{45.6, 45.8, -121.6, -121.4});
}

json resolved(std::string_view cmd, const json& request, geo::Surface* terrain) {
    auto r = session::resolve_ground_altitudes(cmd, request, terrain);
    INFO(request.dump() << " -> " << (r ? r->dump() : r.error().message));
    REQUIRE(r);
    return *r;
}

command::Error refused(std::string_view cmd, const json& request, geo::Surface* terrain) {
    auto r = session::resolve_ground_altitudes(cmd, request, terrain);
    INFO(request.dump());
    REQUIRE_FALSE(r);
    return r.error();
}

}  // namespace

TEST_CASE("ground altitudes: geopoint", "[ground_altitude]") {
    auto terrain = slope();
    // Left out: the terrain's height there.
    json r = resolved("geopoint", {{"lat", 45.71}, {"lon", -121.5}, {"stare", true}}, &terrain);
    CHECK(r["alt"].get<double>() == Approx(410));
    CHECK(r["alt_ref"] == "wgs84");
    CHECK(r["stare"] == true);
    // Height above the ground.
    r = resolved("geopoint", {{"lat", 45.69}, {"lon", -121.5}, {"alt", 25}, {"alt_ref", "terrain"}},
                 &terrain);
    CHECK(r["alt"].get<double>() == Approx(415));
    CHECK(r["alt_ref"] == "wgs84");
    r = resolved("geopoint", {{"lat", 45.69}, {"lon", -121.5}, {"alt_ref", "terrain"}}, &terrain);
    CHECK(r["alt"].get<double>() == Approx(390));
    // Given altitudes pass unchanged, with or without a terrain.
    const json given = {{"lat", 45.7}, {"lon", -121.5}, {"alt", 300}, {"alt_ref", "msl"}};
    CHECK(resolved("geopoint", given, &terrain) == given);
    CHECK(resolved("geopoint", given, nullptr) == given);
    // Anything else malformed is left for the planner to name.
    const json odd = {{"lat", "north"}, {"lon", -121.5}, {"alt", 3}};
    CHECK(resolved("geopoint", odd, &terrain) == odd);
    // Other commands pass unchanged.
    CHECK(resolved("position", {{"pan", 1}}, &terrain) == json{{"pan", 1}});
}

TEST_CASE("ground altitudes: refusals", "[ground_altitude]") {
    auto terrain = slope();
    auto e = refused("geopoint", {{"lat", 46.5}, {"lon", -121.5}}, &terrain);
    CHECK(e.code == ErrorCode::unavailable);
    CHECK_THAT(e.message, Catch::Contains("46.5") && Catch::Contains("'alt'"));
    e = refused("geopoint", {{"lat", 45.7}, {"lon", -121.5}}, nullptr);
    CHECK(e.code == ErrorCode::unavailable);
    CHECK_THAT(e.message, Catch::Contains("none is configured") && Catch::Contains("'alt'"));
    e = refused("geopoint", {{"lat", 45.7}, {"lon", -121.5}, {"alt", 5}, {"alt_ref", "terrain"}},
                nullptr);
    CHECK(e.code == ErrorCode::unavailable);
    CHECK_THAT(e.message, Catch::Contains("alt_ref 'terrain'"));
    e = refused("geopoint", {{"lat", 45.7}, {"lon", -121.5}, {"alt_ref", "msl"}}, &terrain);
    CHECK(e.code == ErrorCode::bad_request);
    CHECK_THAT(e.message, Catch::Contains("'alt'"));
    e = refused("geopoint", {{"lat", 45.7}, {"lon", -121.5}, {"alt_ref", "agl"}}, &terrain);
    CHECK(e.code == ErrorCode::bad_request);
    CHECK_THAT(e.message, Catch::Contains("'alt_ref'"));
    e = refused("path", {{"points", json::array()}, {"alt_ref", "msl"}}, &terrain);
    CHECK_THAT(e.message, Catch::Contains("'alt_ref'"));
    e = refused("geopoint", {{"lat", 91}, {"lon", -121.5}}, &terrain);
    CHECK(e.code == ErrorCode::out_of_range);
    CHECK_THAT(e.message, Catch::Contains("'lat'"));
    e = refused("geopoint", {{"lon", -121.5}}, &terrain);
    CHECK(e.code == ErrorCode::bad_request);
    CHECK_THAT(e.message, Catch::Contains("'lat'"));
    e = refused("geopoint", {{"lat", 45.7}, {"lon", -121.5}, {"alt", "5"}, {"alt_ref", "terrain"}},
                &terrain);
    CHECK(e.code == ErrorCode::bad_request);
    CHECK_THAT(e.message, Catch::Contains("'alt'"));
}

TEST_CASE("ground altitudes: path points", "[ground_altitude]") {
    auto terrain = slope();
    const json points = json::array(
        {{{"lat", 45.71}, {"lon", -121.5}}, {{"lat", 45.72}, {"lon", -121.5}, {"alt", 333}}});
    json r = resolved("path", {{"points", points}, {"cross_steps", 2}}, &terrain);
    CHECK(r["points"][0]["alt"].get<double>() == Approx(410));
    CHECK(r["points"][1]["alt"] == 333);  // given: kept
    CHECK(r["cross_steps"] == 2);
    r = resolved("path", {{"points", points}, {"alt_ref", "terrain"}}, &terrain);
    CHECK(r["points"][0]["alt"].get<double>() == Approx(410));
    CHECK(r["points"][1]["alt"].get<double>() == Approx(420 + 333));
    CHECK(r["alt_ref"] == "wgs84");
    // Every point given: unchanged.
    const json plain = {{"points", json::array({{{"lat", 1}, {"lon", 2}, {"alt", 3}}})}};
    CHECK(resolved("path", plain, nullptr) == plain);
    CHECK(resolved("path", {{"down", true}}, nullptr) == json{{"down", true}});
    // A point the terrain cannot answer is named.
    const auto e = refused(
        "path",
        {{"points", json::array({{{"lat", 45.71}, {"lon", -121.5}}, {{"lat", 47}, {"lon", 0}}})}},
        &terrain);
    CHECK(e.code == ErrorCode::unavailable);
    CHECK_THAT(e.message, Catch::StartsWith("points[1]: "));
    // Malformed points are the planner's to name.
    const json junk = {{"points", json::array({1, 2})}};
    CHECK(resolved("path", junk, &terrain) == junk);
}
