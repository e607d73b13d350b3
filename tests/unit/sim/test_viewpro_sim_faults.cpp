// gimbal-sim's byte faults on a Viewpro gimbal's output: corrupted checksums and junk that
// the output framer must count and skip without losing the frames around them.
#include <catch2/catch.hpp>

#include "protocols/viewpro/codec/output.hpp"
#include "protocols/viewpro/codec/output_framer.hpp"
#include "protocols/viewpro/sim/viewpro_fault_frames.hpp"
#include "sim/fault_injector.hpp"

using namespace gimbal;
using Bytes = std::vector<std::uint8_t>;

namespace {

Bytes stream_of_frames(int n) {
    Bytes out;
    for (int i = 0; i < n; ++i) {
        viewpro::Output o;
        o.format = static_cast<viewpro::OutFormat>(i % 4);
        o.gimbal_yaw_deg = i;
        o.target_lat_deg = 10 + i * 0.001;
        const Bytes f = viewpro::encode_output(o);
        out.insert(out.end(), f.begin(), f.end());
    }
    return out;
}

}  // namespace

TEST_CASE("no faults: the bytes pass unchanged", "[sim][viewpro][faults]") {
    sim::FaultInjector faults({}, sim::viewpro_output_frames());
    CHECK_FALSE(faults.active());
    const Bytes in = stream_of_frames(20);
    Bytes out;
    faults.apply(in, out);
    CHECK(out == in);
    CHECK(faults.stats().frames == 20);
}

TEST_CASE("corrupted frames fail their checksum; the rest come through", "[sim][viewpro][faults]") {
    sim::FaultOptions o;
    o.corrupt_fraction = 0.3;
    o.seed = 5;
    sim::FaultInjector faults(o, sim::viewpro_output_frames());
    Bytes out;
    faults.apply(stream_of_frames(400), out);
    viewpro::OutputFramer framer;
    const auto frames = framer.push(out);
    CHECK(faults.stats().frames == 400);
    CHECK(faults.stats().corrupted > 60);
    CHECK(faults.stats().corrupted < 180);
    CHECK(frames.size() == 400 - faults.stats().corrupted);
    CHECK(framer.stats().bad_checksums >= faults.stats().corrupted);
}

TEST_CASE("junk between frames is dropped and every frame survives", "[sim][viewpro][faults]") {
    sim::FaultOptions o;
    o.junk_every = 3;
    o.seed = 9;
    sim::FaultInjector faults(o, sim::viewpro_output_frames());
    const Bytes in = stream_of_frames(300);
    Bytes out;
    faults.apply(in, out);
    CHECK(faults.stats().junk_inserts == 100);
    viewpro::OutputFramer framer;
    const auto frames = framer.push(out);
    // With this seed no junk happens to complete a checksum-valid false frame (one in 256
    // false headers would), so every frame comes through and exactly the junk is dropped.
    CHECK(frames.size() == 300);
    CHECK(framer.pending_bytes() == 0);
    CHECK(framer.stats().dropped_bytes == out.size() - in.size());
    CHECK(framer.stats().dropped_bytes > 100);
}
