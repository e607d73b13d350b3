// gimbal-sim's read faults: a stall window after each session start, and a line-rate limit.
#include <catch2/catch.hpp>

#include "sim/read_faults.hpp"

using gimbal::sim::ReadFaultOptions;
using gimbal::sim::ReadGate;

TEST_CASE("read gate: no faults reads everything at once", "[sim][faults]") {
    ReadGate gate(ReadFaultOptions{});
    CHECK_FALSE(gate.active());
    gate.session_start(3.0);
    CHECK(gate.budget(3.0).bytes == ReadGate::unlimited);
    gate.consumed(100000, 3.0);
    CHECK(gate.budget(3.0).bytes == ReadGate::unlimited);
}

TEST_CASE("read gate: the stall window counts from each session start", "[sim][faults]") {
    ReadGate gate(ReadFaultOptions{.stall_after_s = 1.0, .stall_for_s = 2.0});
    CHECK(gate.active());
    gate.session_start(10.0);
    CHECK_FALSE(gate.stalled(10.9));
    CHECK(gate.budget(10.9).bytes > 0);
    CHECK(gate.stalled(11.0));
    const auto b = gate.budget(11.5);
    CHECK(b.bytes == 0);
    CHECK(b.retry_after_s == Approx(1.5));
    CHECK_FALSE(gate.stalled(13.0));
    CHECK(gate.budget(13.0).bytes > 0);
    gate.session_start(20.0);  // a new client gets the same fault again
    CHECK(gate.stalled(21.5));
}

TEST_CASE("read gate: a baud limit paces reads at 10 bits per byte", "[sim][faults]") {
    ReadGate gate(ReadFaultOptions{.baud = 115200});
    gate.session_start(0.0);
    double now = 0.0;
    std::size_t total = 0;
    // Read as fast as the gate allows for one simulated second.
    while (now < 1.0) {
        const auto b = gate.budget(now);
        if (b.bytes == 0) {
            now += b.retry_after_s;
            continue;
        }
        CHECK(b.bytes <= 64);
        gate.consumed(b.bytes, now);
        total += b.bytes;
    }
    CHECK(total >= 11520 - 64);
    CHECK(total <= 11520 + 64);
}
