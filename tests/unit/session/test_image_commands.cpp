// The image commands (session/image_commands.hpp) on a gimbal's typed state through its
// capabilities: image positions read and checked, locate and project as inverses, the
// pointing request through the geopoint capability, and every refusal named.
#include <catch2/catch.hpp>
#include <cmath>

#include "protocols/orion/orion_capabilities.hpp"
#include "protocols/viewpro/viewpro_capabilities.hpp"
#include "session/image_commands.hpp"

using namespace gimbal;
using command::ErrorCode;
using nlohmann::json;

namespace {

// An Orion's typed state and its capabilities bound to it.
struct Orion {
    state::OrionData data;
    protocols::OrionCapabilities caps{data};
    state::Telemetry& telemetry() { return data.telemetry->shared; }
};

// An Orion 1500 m over 45.7 N 121.5 W, looking 30 degrees down to the north-east, a 1920 x
// 1080 image, its target at 400 m.
std::unique_ptr<Orion> orion_state() {
    auto o = std::make_unique<Orion>();
    state::OrionTelemetry t;
    t.packet.quat = {0.92388, 0.0, 0.0, 0.38268};
    t.packet.pixel_width = 1920;
    t.packet.pixel_height = 1080;
    t.shared.lat = 45.7;
    t.shared.lon = -121.5;
    t.shared.alt = 1500.0;
    t.shared.geoid_undulation = -21.0;
    t.shared.pan = 10.0;
    t.shared.tilt = -30.0;
    t.shared.hfov = 40.0;
    t.shared.vfov = 22.5;
    t.shared.target = state::GeoPoint{45.71, -121.49, 400.0};
    o->data.telemetry = t;
    return o;
}

// A Viewpro (it never reports a field of view) and its capabilities.
const session::Capabilities& viewpro_caps() {
    static const std::optional<viewpro::Output> nothing;
    static const protocols::ViewproCapabilities caps(nothing);
    return caps;
}

command::Result<session::ImagePosition> read(const json& request) {
    command::JsonParams p(request, request.value("cmd", "locate"));
    return session::read_image_position(p);
}

void refused(const json& request, ErrorCode code, const std::string& key) {
    const auto r = read(request);
    INFO(request.dump());
    REQUIRE_FALSE(r);
    CHECK(r.error().code == code);
    CHECK_THAT(r.error().message, Catch::Contains("'" + key + "'"));
}

}  // namespace

TEST_CASE("image commands: image positions", "[image_commands]") {
    auto r = read({{"x", 0.5}, {"y", -1}});
    REQUIRE(r);
    CHECK_FALSE(r->pixels);
    CHECK(r->a == 0.5);
    CHECK(r->b == -1);
    r = read({{"px", 1920}, {"py", 0}});
    REQUIRE(r);
    CHECK(r->pixels);
    refused(json::object(), ErrorCode::bad_request, "x");
    refused({{"x", 0.5}}, ErrorCode::bad_request, "y");
    refused({{"y", 0.5}}, ErrorCode::bad_request, "x");
    refused({{"py", 5}}, ErrorCode::bad_request, "px");
    refused({{"x", 0.5}, {"y", 0}, {"px", 3}}, ErrorCode::bad_request, "px");
    refused({{"x", 1.01}, {"y", 0}}, ErrorCode::out_of_range, "x");
    refused({{"x", 0}, {"y", -1.5}}, ErrorCode::out_of_range, "y");
    refused({{"px", -1}, {"py", 0}}, ErrorCode::out_of_range, "px");
    refused({{"x", "0.5"}, {"y", 0}}, ErrorCode::bad_request, "x");

    const auto view = orion_state()->caps.image();
    REQUIRE(view);
    auto p = session::image_point({true, 960, 540}, *view);
    REQUIRE(p);
    CHECK(p->x == Approx(0));
    CHECK(p->y == Approx(0));
    p = session::image_point({true, 1920, 0}, *view);
    CHECK(p->x == Approx(1));
    CHECK(p->y == Approx(-1));
    auto bad = session::image_point({true, 1921, 0}, *view);
    REQUIRE_FALSE(bad);
    CHECK(bad.error().code == ErrorCode::out_of_range);
    CHECK_THAT(bad.error().message, Catch::Contains("'px'") && Catch::Contains("1920"));
    bad = session::image_point({true, 0, 1081}, *view);
    CHECK(bad.error().code == ErrorCode::out_of_range);
    session::ImageView no_size = *view;
    no_size.width_px.reset();
    bad = session::image_point({true, 1, 1}, no_size);
    CHECK(bad.error().code == ErrorCode::unavailable);
    CHECK(session::image_point({false, 0.5, 0.5}, no_size));
}

TEST_CASE("image commands: locate and project are inverses", "[image_commands]") {
    const auto view = orion_state()->caps.image();
    REQUIRE(view);
    CHECK(view->flat_alt_m == 400.0);
    for (const double x : {-1.0, -0.3, 0.0, 0.7, 1.0})
        for (const double y : {-1.0, 0.0, 0.4, 1.0}) {
            INFO(x << ", " << y);
            const auto g = session::locate_point(*view, {x, y}, nullptr);
            REQUIRE(g);
            CHECK(g->surface == geo::SurfaceKind::ellipsoid);
            CHECK(g->point.alt_m == Approx(400).margin(1e-3));
            const json back = session::project_reply(*view, g->point, nullptr);
            CHECK(back["x"].get<double>() == Approx(x).margin(1e-5));
            CHECK(back["y"].get<double>() == Approx(y).margin(1e-5));
            // On the edge itself rounding may fall either side.
            if (std::abs(x) < 1 && std::abs(y) < 1) CHECK(back["visible"] == true);
            CHECK(back["px"].get<double>() == Approx((x + 1) * 960).margin(0.01));
            CHECK(back["py"].get<double>() == Approx((y + 1) * 540).margin(0.01));
        }
    // Behind the camera: no image position.
    const json behind = session::project_reply(*view, {45.6, -121.6, 400}, nullptr);
    CHECK(behind["x"].is_null());
    CHECK(behind["visible"] == false);
    // Beside a narrow image: in front, outside -1..1, not visible.
    session::ImageView narrow = *view;
    narrow.camera.hfov_deg = 1;
    narrow.camera.vfov_deg = 1;
    const json off = session::project_reply(narrow, {45.75, -121.45, 400}, nullptr);
    CHECK(off["x"].is_number());
    CHECK_FALSE(off["visible"].get<bool>());

    // No ground: above the horizon, or no flat world.
    auto up = orion_state();
    up->telemetry().tilt = 20.0;
    auto e = session::locate_point(*up->caps.image(), {0, 0}, nullptr);
    REQUIRE_FALSE(e);
    CHECK(e.error().code == ErrorCode::unavailable);
    CHECK_THAT(e.error().message, Catch::Contains("horizon"));
    auto untargeted = orion_state();
    untargeted->telemetry().target.reset();
    e = session::locate_point(*untargeted->caps.image(), {0, 0}, nullptr);
    REQUIRE_FALSE(e);
    CHECK_THAT(e.error().message, Catch::Contains("no terrain is configured"));
}

TEST_CASE("image commands: what each protocol's image says", "[image_commands]") {
    auto nothing = orion_state();
    nothing->data.telemetry.reset();
    auto none = nothing->caps.image();
    REQUIRE_FALSE(none);
    CHECK(none.error().code == ErrorCode::unavailable);
    auto blind = orion_state();
    blind->telemetry().hfov = 0.0;
    none = blind->caps.image();
    REQUIRE_FALSE(none);
    CHECK(none.error().code == ErrorCode::unavailable);
    // Viewpro output frames carry no field of view: never.
    const auto viewpro = viewpro_caps().image();
    REQUIRE_FALSE(viewpro);
    CHECK(viewpro.error().code == ErrorCode::unsupported);
}

TEST_CASE("image commands: point goes through the geopoint capability", "[image_commands]") {
    const auto orion = orion_state();
    const auto& caps = orion->caps;
    const auto view = caps.image();
    REQUIRE(view);
    const auto g = session::locate_point(*view, {0.5, -0.3}, nullptr);
    REQUIRE(g);
    auto r = session::point_request(caps, *view, *g, false);
    REQUIRE(r);
    CHECK((*r)["cmd"] == "geopoint");
    CHECK((*r)["lat"].get<double>() == Approx(g->point.lat_deg));
    CHECK((*r)["lon"].get<double>() == Approx(g->point.lon_deg));
    // MSL with the gimbal's own undulation: its planner turns it back into 400 m WGS84.
    CHECK((*r)["alt"].get<double>() + -21.0 == Approx(400).margin(1e-3));
    CHECK((*r)["alt_ref"] == "msl");
    CHECK_FALSE(r->contains("stare"));
    r = session::point_request(caps, *view, *g, true);
    REQUIRE(r);
    CHECK((*r)["stare"] == true);

    // A gimbal without the geopoint capability: unsupported.
    const auto vp = session::point_request(viewpro_caps(), *view, *g, false);
    REQUIRE_FALSE(vp);
    CHECK(vp.error().code == ErrorCode::unsupported);
    // No undulation to give an MSL altitude with: not yet.
    session::ImageView no_geoid = *view;
    no_geoid.geoid_undulation_m.reset();
    const auto later = session::point_request(caps, no_geoid, *g, false);
    REQUIRE_FALSE(later);
    CHECK(later.error().code == ErrorCode::unavailable);
}
