#include <catch2/catch.hpp>

#include "protocols/orion/sim/retract.hpp"

using namespace gimbal::sim;
using gimbal::orion::RetractCmd;
using gimbal::orion::RetractState;

TEST_CASE("the retract arm moves at its rate between deployed and retracted", "[sim][retract]") {
    Retract r(1.5, 0.5);
    CHECK(r.state() == RetractState::deployed);
    r.command(RetractCmd::retract);
    CHECK(r.state() == RetractState::retracting);
    r.step(1.0);
    CHECK(r.position() == Approx(0.5));
    r.step(2.5);
    CHECK(r.state() == RetractState::retracted);
    CHECK(r.position() == Approx(1.5));

    r.command(RetractCmd::deploy);
    CHECK(r.state() == RetractState::deploying);
    r.step(1.0);
    r.command(RetractCmd::disable);  // stops where it is
    r.step(5.0);
    CHECK(r.state() == RetractState::disabled);
    CHECK(r.position() == Approx(1.0));
    CHECK(r.last_command() == RetractCmd::disable);

    r.command(RetractCmd::deploy);
    r.step(10);
    CHECK(r.state() == RetractState::deployed);
    CHECK(r.position() == 0);
}

TEST_CASE("an undefined retract command is a fault", "[sim][retract]") {
    Retract r;
    r.command(static_cast<RetractCmd>(9));
    CHECK(r.state() == RetractState::fault);
}
