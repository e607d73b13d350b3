#include <catch2/catch.hpp>

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/sim/orion_fault_frames.hpp"
#include "sim/fault_injector.hpp"

using namespace gimbal;
using Bytes = std::vector<std::uint8_t>;

namespace {
Bytes frames(int n) {
    Bytes out;
    for (int i = 0; i < n; ++i) {
        const Bytes data(static_cast<std::size_t>(i % 20), static_cast<std::uint8_t>(i));
        orion::append_frame(static_cast<std::uint8_t>(i), data, out);
    }
    return out;
}
}  // namespace

TEST_CASE("no faults: bytes pass unchanged", "[sim][faults]") {
    sim::FaultInjector f(sim::FaultOptions{}, sim::orion_frames());
    const Bytes in = frames(50);
    Bytes out;
    f.apply(in, out);
    CHECK(out == in);
    CHECK(f.stats().frames == 50);
    CHECK_FALSE(f.active());
}

TEST_CASE("corrupt_fraction breaks that share of checksums", "[sim][faults]") {
    sim::FaultInjector all({1.0, 0, 7}, sim::orion_frames());
    Bytes out;
    all.apply(frames(100), out);
    orion::Framer framer;
    CHECK(framer.push(out).empty());
    CHECK(framer.stats().bad_checksums == 100);

    sim::FaultInjector some({0.3, 0, 7}, sim::orion_frames());
    out.clear();
    some.apply(frames(1000), out);
    orion::Framer framer2;
    const auto got = framer2.push(out);
    CHECK(some.stats().corrupted > 200);
    CHECK(some.stats().corrupted < 400);
    CHECK(got.size() == 1000 - some.stats().corrupted);
}

TEST_CASE("junk between frames costs no valid frame", "[sim][faults]") {
    sim::FaultInjector f({0, 3, 11}, sim::orion_frames());
    const Bytes in = frames(300);
    Bytes out;
    f.apply(in, out);
    CHECK(out.size() > in.size());
    CHECK(f.stats().junk_inserts == 100);
    orion::Framer framer;
    CHECK(framer.push(out).size() == 300);
    CHECK(framer.stats().dropped_bytes > 0);
}

TEST_CASE("bytes that are not frames pass through", "[sim][faults]") {
    sim::FaultInjector f({1.0, 1, 3}, sim::orion_frames());
    const Bytes in{0x01, 0xD0, 0x0D, 0x05};  // a cut-off header
    Bytes out;
    f.apply(in, out);
    CHECK(out == in);
}
