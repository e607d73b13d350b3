#include <catch2/catch.hpp>

#include "protocols/orion/sim/laser.hpp"

using namespace gimbal::sim;
using gimbal::orion::LaserType;

namespace {
LaserRequest request(bool enable, bool arm, bool fire, std::string password = "") {
    LaserRequest r;
    r.enable = enable;
    r.arm = arm;
    r.fire = fire;
    r.password = std::move(password);
    return r;
}
}  // namespace

TEST_CASE("a laser fires only when enabled and armed", "[sim][laser]") {
    LaserBank bank({LaserType::pointer}, "");
    CHECK(bank.command(request(false, false, true)) == LaserResult::fire_refused);
    CHECK_FALSE(bank.units()[0].active);

    CHECK(bank.command(request(true, false, true)) == LaserResult::fire_refused);
    CHECK(bank.units()[0].enabled);
    CHECK_FALSE(bank.units()[0].active);

    CHECK(bank.command(request(false, true, false)) == LaserResult::arm_refused);
    CHECK_FALSE(bank.units()[0].armed);

    CHECK(bank.command(request(true, true, true)) == LaserResult::applied);
    CHECK(bank.units()[0].armed);
    CHECK(bank.units()[0].active);

    CHECK(bank.command(request(true, true, false)) == LaserResult::applied);
    CHECK_FALSE(bank.units()[0].active);
    CHECK(bank.units()[0].armed);
}

TEST_CASE("a configured password guards every change", "[sim][laser]") {
    LaserBank bank({LaserType::pointer, LaserType::lightware}, "s3cret");
    CHECK(bank.command(request(true, true, true)) == LaserResult::wrong_password);
    CHECK(bank.units()[0].password_lock);
    CHECK_FALSE(bank.units()[0].enabled);

    CHECK(bank.command(request(true, true, true, "wrong")) == LaserResult::wrong_password);
    CHECK_FALSE(bank.units()[0].active);

    CHECK(bank.command(request(true, true, true, "s3cret")) == LaserResult::applied);
    CHECK(bank.units()[0].active);
    CHECK_FALSE(bank.units()[0].password_lock);

    // A wrong password cannot stop it either: nothing changes.
    CHECK(bank.command(request(false, false, false, "nope")) == LaserResult::wrong_password);
    CHECK(bank.units()[0].active);
}

TEST_CASE("lasers are independent and out-of-range indexes are refused", "[sim][laser]") {
    LaserBank bank({LaserType::pointer, LaserType::lightware}, "");
    auto r = request(true, true, true);
    r.index = 1;
    r.safety_bypass = true;
    CHECK(bank.command(r) == LaserResult::applied);
    CHECK(bank.units()[1].active);
    CHECK(bank.units()[1].bypass);
    CHECK_FALSE(bank.units()[0].active);
    r.index = 2;
    CHECK(bank.command(r) == LaserResult::no_such_laser);
}
