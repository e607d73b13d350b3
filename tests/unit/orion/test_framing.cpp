#include <catch2/catch.hpp>
#include <vector>

#include "orion/framer.hpp"
#include "orion/framing.hpp"
#include "orion/packets.hpp"

using namespace gimbal::orion;
using Bytes = std::vector<std::uint8_t>;

TEST_CASE("Fletcher-251 matches the ICD's reference vector", "[orion][checksum]") {
    const Bytes header{0xD0, 0x0D, 0x28, 0x00};
    CHECK(fletcher251(header) == 0x0BCA);
    CHECK(request_bytes(pkt::crown_version) == Bytes{0xD0, 0x0D, 0x28, 0x00, 0x0B, 0xCA});
}

TEST_CASE("framer delivers packets split at every byte offset", "[orion][framer]") {
    const Bytes a = frame_bytes(212, Bytes(46, 0x5A));
    const Bytes b = frame_bytes(1, Bytes{1, 2, 3, 4, 5, 6, 7});
    Bytes stream = a;
    stream.insert(stream.end(), b.begin(), b.end());
    for (std::size_t cut = 0; cut <= stream.size(); ++cut) {
        Framer f;
        std::vector<Frame> got;
        auto sink = [&](const Frame& fr) { got.push_back(fr); };
        f.push({stream.data(), cut}, sink);
        f.push({stream.data() + cut, stream.size() - cut}, sink);
        REQUIRE(got.size() == 2);
        CHECK(got[0].id == 212);
        CHECK(got[0].payload.size == 46);
        CHECK(got[1].id == 1);
        CHECK(f.stats().dropped_bytes == 0);
    }
}
