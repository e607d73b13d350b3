// Laser rules 4 and 5 of contract section 4.2, with time passed in.
#include <catch2/catch.hpp>

#include "session/laser_guard.hpp"

using gimbal::command::LaserIntent;
using gimbal::session::LaserGuard;

namespace {
LaserIntent intent(std::uint8_t index, bool fire) {
    return LaserIntent{index, fire, {0xD0, 0x0D, 3, index}};
}
}  // namespace

TEST_CASE("dead-man: a fire without a follow-up ceases after fire_timeout_s", "[laser]") {
    LaserGuard guard(5.0);
    guard.commanded(intent(0, true), 10.0);
    CHECK(guard.firing(0));
    CHECK(guard.next_deadline() == Approx(15.0));
    CHECK(guard.expired(14.99).empty());
    auto ceases = guard.expired(15.0);
    REQUIRE(ceases.size() == 1);
    CHECK(ceases[0].index == 0);
    CHECK(ceases[0].frame == std::vector<std::uint8_t>{0xD0, 0x0D, 3, 0});
    CHECK(guard.expired(16.0).empty());  // reported once
    CHECK(guard.firing(0));              // until the caller confirms the cease was written
    guard.ceased(0);
    CHECK_FALSE(guard.firing(0));
    CHECK_FALSE(guard.next_deadline());
}

TEST_CASE("dead-man: any further laser command for the index re-arms or clears it", "[laser]") {
    LaserGuard guard(2.0);
    guard.commanded(intent(1, true), 0.0);
    guard.commanded(intent(1, true), 1.5);
    CHECK(guard.expired(2.5).empty());
    CHECK(guard.next_deadline() == Approx(3.5));
    guard.commanded(intent(1, false), 3.0);
    CHECK_FALSE(guard.firing(1));
    CHECK(guard.expired(10.0).empty());
}

TEST_CASE("cease_all lists every index last commanded to fire", "[laser]") {
    LaserGuard guard(5.0);
    guard.commanded(intent(0, true), 0.0);
    guard.commanded(intent(1, true), 0.0);
    guard.commanded(intent(1, false), 1.0);
    auto all = guard.cease_all();
    REQUIRE(all.size() == 1);
    CHECK(all[0].index == 0);
    // A dead-man cease that could not be written stays pending for the reconnect.
    CHECK(guard.expired(6.0).size() == 1);
    CHECK(guard.cease_all().size() == 1);
    guard.ceased(0);
    CHECK(guard.cease_all().empty());
    guard.commanded(intent(5, true), 0.0);  // out of range indexes are ignored
    CHECK(guard.cease_all().empty());
}

TEST_CASE("a cease-fire counts only once written, and never for a newer command", "[laser]") {
    LaserGuard guard(1.0);
    guard.commanded(intent(0, true), 0.0);
    auto ceases = guard.expired(1.0);
    REQUIRE(ceases.size() == 1);
    const auto cease = ceases[0];
    guard.cease_queued(cease, 1.0);
    CHECK(guard.firing(0));  // queued is not written
    CHECK(guard.overdue(1.4, 0.5).empty());
    CHECK(guard.overdue(1.6, 0.5) == std::vector<std::uint8_t>{0});
    CHECK(guard.overdue(2.0, 0.5).empty());  // reported once
    CHECK(guard.ceased(cease));
    CHECK_FALSE(guard.firing(0));

    // A new fire command queued behind a pending cease-fire: the cease must not end it.
    guard.commanded(intent(1, true), 0.0);
    const auto old = guard.expired(1.0).at(0);
    guard.cease_queued(old, 1.0);
    guard.commanded(intent(1, true), 1.2);
    CHECK_FALSE(guard.ceased(old));
    CHECK(guard.firing(1));
    CHECK(guard.next_deadline() == Approx(2.2));
    CHECK(guard.overdue(5.0, 0.5).empty());  // the old cease no longer waits

    // Discarded by a disconnect: still firing, for the reconnect's cease_all().
    const auto again = guard.expired(2.2).at(0);
    guard.cease_queued(again, 2.2);
    guard.cease_discarded(again);
    CHECK(guard.firing(1));
    CHECK(guard.overdue(9.0, 0.5).empty());
    REQUIRE(guard.cease_all().size() == 1);
    CHECK(guard.cease_all()[0].serial == again.serial);
}
