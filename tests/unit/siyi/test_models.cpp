// The model table: identification by hardware id, limits, fields of view.
#include <catch2/catch.hpp>
#include <cmath>

#include "protocols/siyi/codec/models.hpp"

using namespace gimbal::siyi;

namespace {
constexpr double deg = 3.14159265358979323846 / 180.0;
}

TEST_CASE("a hardware id names its model by its first two characters", "[siyi][models]") {
    // SDK v0.1.1, 0x02: 6B ZR10, 73 A8 mini, 78 ZR30, 7A quad-sensor (ZT30); ArduPilot: 82 ZT6.
    CHECK(model_from_hardware_id("6B01234567") == Model::zr10);
    CHECK(model_from_hardware_id("7301234567") == Model::a8_mini);
    CHECK(model_from_hardware_id("7801234567") == Model::zr30);
    CHECK(model_from_hardware_id("7A01234567") == Model::zt30);
    CHECK(model_from_hardware_id("7a01234567") == Model::zt30);
    CHECK(model_from_hardware_id("8201234567") == Model::zt6);
    CHECK_FALSE(model_from_hardware_id("7501234567"));  // A2 mini: not a model gimbald drives
    CHECK_FALSE(model_from_hardware_id("7"));
    CHECK_FALSE(model_from_hardware_id(""));
    for (const Model m : all_models) CHECK(model_from_hardware_id(model_info(m).id_prefix) == m);
}

TEST_CASE("models are found by key", "[siyi][models]") {
    for (const Model m : all_models) {
        CHECK(model_from_key(model_info(m).key) == m);
        CHECK(model_info(m).model == m);
    }
    CHECK(model_from_key("ZT30") == Model::zt30);
    CHECK(model_from_key("A8MINI") == Model::a8_mini);
    CHECK_FALSE(model_from_key("zt31"));
}

TEST_CASE("angle limits follow the SDK's 0x0E table", "[siyi][models]") {
    for (const Model m : all_models) {
        CHECK(model_info(m).pitch_min == -90);
        CHECK(model_info(m).pitch_max == 25);
    }
    CHECK(model_info(Model::a8_mini).yaw_max == 135);
    CHECK(model_info(Model::zr10).yaw_min == -135);
    CHECK(model_info(Model::zr30).yaw_max == 270);
    CHECK(model_info(Model::zt30).yaw_continuous);
    CHECK(model_info(Model::zt30).has_laser);
    CHECK_FALSE(model_info(Model::zr30).has_laser);
}

TEST_CASE("the field of view narrows as tan(fov/2) / zoom", "[siyi][models][fov]") {
    const auto a8 = field_of_view(Model::a8_mini, 1);
    CHECK(a8.hfov_deg == Approx(81.2));
    CHECK(std::tan(a8.vfov_deg * deg / 2) == Approx(std::tan(81.2 * deg / 2) * 9 / 16));
    const auto a8x2 = field_of_view(Model::a8_mini, 2);
    CHECK(std::tan(a8x2.hfov_deg * deg / 2) == Approx(std::tan(81.2 * deg / 2) / 2));
    // Clamped to the model's range.
    CHECK(field_of_view(Model::a8_mini, 100).hfov_deg ==
          Approx(field_of_view(Model::a8_mini, 6).hfov_deg));
    CHECK(field_of_view(Model::zt30, 0.2).hfov_deg == Approx(57.3));
    CHECK(field_of_view(Model::zt30, std::nan("")).hfov_deg == Approx(57.3));
    const auto tele = field_of_view(Model::zt30, 30);
    CHECK(tele.hfov_deg == Approx(2.0 * std::atan(std::tan(57.3 * deg / 2) / 30) / deg));
    CHECK(tele.hfov_deg < 2.2);
}

TEST_CASE("wrap180", "[siyi][models]") {
    CHECK(wrap180(0) == 0);
    CHECK(wrap180(180) == -180);
    CHECK(wrap180(-180) == -180);
    CHECK(wrap180(190) == Approx(-170));
    CHECK(wrap180(-190) == Approx(170));
    CHECK(wrap180(720 + 10) == Approx(10));
}
