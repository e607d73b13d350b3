// The typed STATE's one JSON writer (state/writer.hpp): a struct's fields() visit written with
// the contract's precision per unit, null for what is not known, nested parts and arrays;
// delta patches come from what it writes.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "state/merge_patch.hpp"
#include "state/writer.hpp"

using nlohmann::json;
namespace state = gimbal::state;

namespace {

struct Point {
    double lat = 0, lon = 0;
    std::optional<double> alt;
};

template <class V>
void fields(V& v, const Point& p) {
    v.latlon("lat", p.lat);
    v.latlon("lon", p.lon);
    v.metres("alt", p.alt);
}

struct Part {
    std::string name = "cam";
    bool connected = true;
    std::uint64_t packets = 18446744073709551615ull;
    int width = -3;
    std::optional<int> height;
    double pan = 12.3456789;
    std::optional<double> tilt;
    double age = 0.00049;
    double rate = 29.97002997;
    double raw = 0.1 + 0.2;
    std::optional<Point> target;
    std::vector<Point> corners;
    std::array<double, 3> rates{1.00005, -2.5, 0};
    std::vector<std::string> flags{"a", "b"};
    std::optional<std::string> error;
};

template <class V>
void fields(V& v, const Part& p) {
    v.string("name", p.name);
    v.boolean("connected", p.connected);
    v.integer("packets", p.packets);
    v.integer("width", p.width);
    v.integer("height", p.height);
    v.angle("pan", p.pan);
    v.angle("tilt", p.tilt);
    v.seconds("age_s", p.age);
    v.decimals("fps", p.rate, 3);
    v.number("raw", p.raw);
    v.object("target", p.target);
    v.array("corners", p.corners, [](const Point& c) { return state::write(c); });
    v.array("rates", p.rates, state::angle_json);
    v.array("flags", p.flags);
    v.string("error", p.error);
    v.object("inline", [](state::JsonWriter& w) { w.null("nothing"); });
}

}  // namespace

TEST_CASE("the writer: every unit at the contract's precision, null for the unknown") {
    Part p;
    p.corners = {{45.12345678, -121.00000004, 12.3456}, {-0.00000005, 179.99999999, {}}};
    const json j = state::write(p);
    CHECK(j.dump() ==
          R"({"age_s":0.0,"connected":true,"corners":[{"alt":12.346,"lat":45.1234568,)"
          R"("lon":-121.0},{"alt":null,"lat":-1e-07,"lon":180.0}],"error":null,"flags":["a","b"],)"
          R"("fps":29.97,"height":null,"inline":{"nothing":null},"name":"cam",)"
          R"("packets":18446744073709551615,"pan":12.3457,"rates":[1.0001,-2.5,0.0],)"
          R"("raw":0.30000000000000004,"target":null,"tilt":null,"width":-3})");
    CHECK(j["packets"].is_number_unsigned());
    CHECK(j["width"].is_number_integer());

    p.target = Point{1.5, 2.25, 3};
    p.tilt = -90;
    p.height = 1080;
    p.error = "x";
    const json k = state::write(p);
    CHECK(k["target"].dump() == R"({"alt":3.0,"lat":1.5,"lon":2.25})");
    CHECK(k["tilt"].dump() == "-90.0");
    CHECK(k["height"] == 1080);
    CHECK(k["error"] == "x");
}

TEST_CASE("the writer: rounding twice changes nothing, non-finite numbers print as null") {
    Point p{45.1234567, -121.9876543, 1234.567};
    const json once = state::write(p);
    Point again{once["lat"].get<double>(), once["lon"].get<double>(), once["alt"].get<double>()};
    CHECK(state::write(again).dump() == once.dump());
    p.alt = std::numeric_limits<double>::quiet_NaN();
    CHECK(state::write(p).dump() == R"({"alt":null,"lat":45.1234567,"lon":-121.9876543})");
}

TEST_CASE("the writer into an existing object: members added and replaced, codec JSON kept") {
    json out = {{"kept", 1}, {"lat", "old"}};
    state::JsonWriter w(out);
    w.latlon("lat", 10.000000049);
    w.json("packet", {{"x", 1}});
    w.members({{"y", 2}, {"kept", 3}});
    CHECK(out.dump() == R"({"kept":3,"lat":10.0,"packet":{"x":1},"y":2})");
    json not_object = 5;
    state::JsonWriter again(not_object);
    again.boolean("b", false);
    CHECK(not_object.dump() == R"({"b":false})");
}

TEST_CASE("delta patches are merge patches of two written snapshots") {
    Part a;
    Part b = a;
    b.pan = 12.34574;  // the same at 1e-4 degree: no change
    CHECK(state::merge_patch_diff(state::write(a), state::write(b)).dump() == "{}");
    b.pan = 13;
    b.target = Point{1, 2, std::nullopt};
    const json patch = state::merge_patch_diff(state::write(a), state::write(b));
    CHECK(patch.dump() == R"({"pan":13.0,"target":{"alt":null,"lat":1.0,"lon":2.0}})");
    json applied = state::write(a);
    state::merge_patch_apply(applied, patch);
    CHECK(state::same_ignoring_age(applied, state::write(b)));
}
