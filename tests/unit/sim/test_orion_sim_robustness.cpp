// The simulated Orion under bad input and odd clocks: nothing crashes, nothing changes.
#include <catch2/catch.hpp>
#include <random>

#include "protocols/orion/codec/packets.hpp"
#include "sim_harness.hpp"

using namespace gimbal;
using namespace sim_test;
namespace pkt = orion::pkt;

namespace {

// Noise with plenty of sync bytes, false headers and bad checksums in it.
Bytes garbage(std::mt19937& rng, std::size_t n) {
    std::uniform_int_distribution<int> byte(0, 255);
    Bytes out;
    for (std::size_t i = 0; i < n; ++i) {
        const int b = byte(rng);
        if (b < 20) {
            out.insert(out.end(), {0xD0, 0x0D, static_cast<std::uint8_t>(byte(rng)),
                                   static_cast<std::uint8_t>(byte(rng) % 150)});
        } else if (b < 40) {
            out.push_back(0xD0);
        } else {
            out.push_back(static_cast<std::uint8_t>(byte(rng)));
        }
    }
    return out;
}

}  // namespace

TEST_CASE("garbage input neither crashes the gimbal nor changes what it does",
          "[sim][orion][robustness]") {
    Harness clean;
    Harness dirty;
    std::mt19937 rng(1234);
    clean.run(0);
    dirty.run(0);
    for (int i = 0; i < 500; ++i) {  // 10 s
        dirty.send(garbage(rng, 64));
        clean.run(0.02);
        dirty.run(0.02);
    }
    CHECK(clean.raw() == dirty.raw());
}

TEST_CASE("valid packets amid garbage and any chunking still work", "[sim][orion][robustness]") {
    Harness h;
    std::mt19937 rng(99);
    h.run(0.5);
    orion::Cmd c;
    c.cmd.mode = orion::Mode::scene;
    Bytes stream = garbage(rng, 200);
    const Bytes wire = orion::to_wire(c);
    stream.insert(stream.end(), wire.begin(), wire.end());
    const Bytes tail = garbage(rng, 50);
    stream.insert(stream.end(), tail.begin(), tail.end());
    for (std::size_t i = 0; i < stream.size(); i += 3)
        h.send(Bytes(stream.begin() + static_cast<long>(i),
                     stream.begin() + static_cast<long>(std::min(i + 3, stream.size()))));
    const auto frames = h.run(0.3);
    CHECK(count_id(frames, pkt::cmd) == 1);
    const auto t = decoded<orion::GeolocateTelemetry>(frames);
    REQUIRE(!t.empty());
    CHECK(t.back().mode == orion::Mode::scene);
}

TEST_CASE("well-framed packets with bad contents are ignored", "[sim][orion][robustness]") {
    Harness clean;
    Harness dirty;
    clean.run(0.5);
    dirty.run(0.5);
    // Too short for their declarations, or with values no command uses.
    dirty.send(orion::frame_bytes(pkt::cmd, Bytes{1, 2, 3}));
    dirty.send(orion::frame_bytes(pkt::geopoint_cmd, Bytes(10, 0xFF)));
    dirty.send(orion::frame_bytes(pkt::laser_cmd, Bytes{0, 0, 9}));
    dirty.send(orion::frame_bytes(pkt::path, Bytes{0}));
    dirty.send(orion::frame_bytes(pkt::stare_ack, Bytes{1}));
    dirty.send(orion::frame_bytes(pkt::retract_cmd, Bytes{1}));
    dirty.send(orion::frame_bytes(pkt::camera_state, Bytes{0}));
    dirty.send(orion::frame_bytes(pkt::limits, Bytes(5, 1)));
    orion::Path no_points;  // no points and not pointing down: nothing to do
    dirty.send(orion::to_wire(no_points));
    orion::LaserCmd laser;
    laser.index = 5;  // no such laser
    laser.enable = laser.arm = laser.fire = true;
    dirty.send(orion::to_wire(laser));
    const auto answer = dirty.run(0.001, 0.001);
    clean.run(0.001, 0.001);
    // Only the laser command gets an answer (the states, unchanged).
    CHECK(answer.size() == 1);
    REQUIRE(count_id(answer, pkt::laser_states) == 1);
    const auto states = decoded<orion::LaserStates>(answer);
    REQUIRE(states.size() == 1);
    for (const auto& s : states[0].states) CHECK_FALSE(s.active);

    const auto a = decoded<orion::GeolocateTelemetry>(clean.run(3.0));
    const auto b = decoded<orion::GeolocateTelemetry>(dirty.run(3.0));
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(orion::to_wire(a[i]) == orion::to_wire(b[i]));
    }
}

TEST_CASE("time that stands still or runs backwards is harmless", "[sim][orion][robustness]") {
    auto device = sim::make_orion_sim();
    Bytes out;
    device->advance(100.0, out);
    const std::size_t first = out.size();
    device->advance(100.0, out);
    device->advance(99.0, out);
    device->advance(std::nan(""), out);
    CHECK(out.size() == first);
    device->advance(100.1, out);
    CHECK(out.size() > first);
}

TEST_CASE("a long silence does not replay hours of output", "[sim][orion][robustness]") {
    auto device = sim::make_orion_sim();
    Bytes out;
    device->advance(0.0, out);
    out.clear();
    device->advance(3600.0, out);
    orion::Framer framer;
    std::size_t telemetry = 0;
    framer.push(out, [&](const orion::Frame& f) { telemetry += f.id == pkt::geolocate_telemetry; });
    CHECK(telemetry >= 600);  // the last minute
    CHECK(telemetry <= 602);
    out.clear();
    device->advance(3600.1, out);
    CHECK(!out.empty());
}

TEST_CASE("the same seed gives the same bytes", "[sim][orion][robustness]") {
    Harness a;
    Harness b;
    a.run(5.0);
    b.run(5.0);
    CHECK(a.raw() == b.raw());
    sim::OrionSimOptions other;
    other.seed = 2;
    Harness c(other);
    c.run(5.0);
    CHECK(c.raw() != a.raw());
}
