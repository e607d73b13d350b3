// The `track` command's parameters (session/track_request.hpp, contract section 20): a point
// with its box of `size` image widths, a box, either in pixels, and every refusal named.
#include <catch2/catch.hpp>
#include <cmath>

#include "session/track_request.hpp"

using namespace gimbal;
using command::ErrorCode;
using nlohmann::json;

namespace {

// A 1920 x 1080 camera with 16:9 fields of view.
session::ImageView view_1080p() {
    session::ImageView v;
    v.camera.hfov_deg = 40;
    v.camera.vfov_deg = 2 * std::atan(std::tan(20 * M_PI / 180) * 9 / 16) * 180 / M_PI;
    v.width_px = 1920;
    v.height_px = 1080;
    return v;
}

command::Result<session::TrackRequest> read(const json& request,
                                            const session::ImageView& view = view_1080p()) {
    command::JsonParams p(request, "track");
    auto r = session::read_track_request(p, view);
    if (r) p.reject_unknown();
    if (!p.ok()) return p.error();
    return r;
}

void refused(const json& request, ErrorCode code, const std::string& words) {
    const auto r = read(request);
    INFO(request.dump());
    REQUIRE_FALSE(r);
    CHECK(r.error().code == code);
    CHECK_THAT(r.error().message, Catch::Contains(words));
}

}  // namespace

TEST_CASE("track: a point gets a square box of 0.08 image widths", "[track]") {
    const auto r = read({{"x", 0.5}, {"y", -0.25}});
    REQUIRE(r);
    CHECK(r->box.x0 == Approx(0.42));
    CHECK(r->box.x1 == Approx(0.58));
    // As many pixels down as across: 0.08 x 1920 = 153.6 px of 1080.
    CHECK((r->box.y1 - r->box.y0) * 540 == Approx((r->box.x1 - r->box.x0) * 960));
    CHECK((r->box.y0 + r->box.y1) / 2 == Approx(-0.25));
    CHECK_FALSE(r->steer.has_value());

    const auto small = read({{"x", 0}, {"y", 0}, {"size", 0.02}, {"steer", false}});
    REQUIRE(small);
    CHECK(small->box.x1 - small->box.x0 == Approx(0.04));
    CHECK(small->steer == std::optional<bool>(false));
}

TEST_CASE("track: a point's box is clipped to the picture", "[track]") {
    const auto r = read({{"x", 0.98}, {"y", -1}});
    REQUIRE(r);
    CHECK(r->box.x1 == 1.0);
    CHECK(r->box.y0 == -1.0);
    CHECK(r->box.x0 == Approx(0.9));
}

TEST_CASE("track: the aspect comes from the fields of view without a pixel size", "[track]") {
    auto v = view_1080p();
    v.width_px.reset();
    v.height_px.reset();
    REQUIRE(session::image_aspect(v));
    CHECK(*session::image_aspect(v) == Approx(16.0 / 9));
    const auto r = read({{"x", 0}, {"y", 0}}, v);
    REQUIRE(r);
    CHECK(r->box.y1 == Approx(0.08 * 16 / 9));
}

TEST_CASE("track: boxes, normalised and in pixels", "[track]") {
    const auto box = read({{"x0", -0.5}, {"y0", -0.25}, {"x1", 0.5}, {"y1", 0.25}});
    REQUIRE(box);
    CHECK(box->box.x0 == -0.5);
    CHECK(box->box.y1 == 0.25);

    const auto pixels = read({{"px0", 480}, {"py0", 270}, {"px1", 1440}, {"py1", 810}});
    REQUIRE(pixels);
    CHECK(pixels->box.x0 == Approx(-0.5));
    CHECK(pixels->box.y0 == Approx(-0.5));
    CHECK(pixels->box.x1 == Approx(0.5));
    CHECK(pixels->box.y1 == Approx(0.5));

    const auto point = read({{"px", 960}, {"py", 540}});
    REQUIRE(point);
    CHECK((point->box.x0 + point->box.x1) / 2 == Approx(0));
}

TEST_CASE("track: refusals name what is wrong", "[track]") {
    refused(json::object(), ErrorCode::bad_request, "missing parameters");
    refused({{"x", 0}, {"y", 0}, {"x0", 0}, {"y0", 0}, {"x1", 1}, {"y1", 1}},
            ErrorCode::bad_request, "give one of");
    refused({{"x0", 0}, {"y0", 0}, {"x1", 0.5}}, ErrorCode::bad_request, "'y1'");
    refused({{"x0", 0.5}, {"y0", 0}, {"x1", 0.1}, {"y1", 0.5}}, ErrorCode::bad_request, "empty");
    refused({{"x0", 0}, {"y0", 0}, {"x1", 0.5}, {"y1", 0.5}, {"size", 0.1}}, ErrorCode::bad_request,
            "'size'");
    refused({{"x", 1.5}, {"y", 0}}, ErrorCode::out_of_range, "x");
    refused({{"x", 0}, {"y", 0}, {"size", 0.9}}, ErrorCode::out_of_range, "size");
    refused({{"x", 0}, {"y", 0}, {"steer", "yes"}}, ErrorCode::bad_request, "steer");
    refused({{"x", 0}, {"y", 0}, {"colour", "red"}}, ErrorCode::bad_request, "colour");
    refused({{"px0", 0}, {"py0", 0}, {"px1", 2000}, {"py1", 500}}, ErrorCode::out_of_range,
            "beyond the image");

    auto no_size = view_1080p();
    no_size.width_px.reset();
    const json pixels = {{"px0", 0}, {"py0", 0}, {"px1", 10}, {"py1", 10}};
    command::JsonParams p(pixels, "track");  // JsonParams keeps a reference
    const auto r = session::read_track_request(p, no_size);
    REQUIRE_FALSE(r);
    CHECK(r.error().code == ErrorCode::unavailable);
}
