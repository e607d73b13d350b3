// The access units since the latest key frame (video/gop_buffer.hpp): what a track started now
// is given first, so it begins on the newest picture.
#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "video/gop_buffer.hpp"

using namespace gimbal::video;

namespace {

struct Stream {
    std::vector<std::vector<std::uint8_t>> payloads;
    AccessUnit unit(std::uint64_t pts, bool key, std::size_t bytes = 100) {
        payloads.emplace_back(bytes, static_cast<std::uint8_t>(pts));
        return {Codec::h264, pts, std::nullopt, key, payloads.back()};
    }
};

std::vector<std::uint64_t> pts_of(const GopBuffer& b) {
    std::vector<std::uint64_t> out;
    for (const auto& u : b.units()) out.push_back(*u.pts);
    return out;
}

}  // namespace

TEST_CASE("gop buffer: from the latest key frame to the newest unit", "[video][gop]") {
    Stream s;
    s.payloads.reserve(64);
    GopBuffer b;
    b.add(s.unit(1, false));  // joined mid-group: nothing to start from
    CHECK(b.units().empty());
    b.add(s.unit(2, true));
    b.add(s.unit(3, false));
    b.add(s.unit(4, false));
    CHECK(pts_of(b) == std::vector<std::uint64_t>{2, 3, 4});
    CHECK(b.bytes() == 300);
    CHECK(b.units().front().key_frame);
    CHECK(b.units()[1].data == std::vector<std::uint8_t>(100, 3));  // a copy, not a view
    b.add(s.unit(5, true));                                         // a new group
    b.add(s.unit(6, false));
    CHECK(pts_of(b) == std::vector<std::uint64_t>{5, 6});
    CHECK(b.bytes() == 200);
    b.clear();
    CHECK(b.units().empty());
    b.add(s.unit(7, false));
    CHECK(b.units().empty());
}

TEST_CASE("gop buffer: a group over its limits is dropped until the next key frame",
          "[video][gop]") {
    Stream s;
    s.payloads.reserve(64);
    GopBuffer b({.max_bytes = 1000, .max_units = 4});
    b.add(s.unit(1, true, 400));
    b.add(s.unit(2, false, 400));
    b.add(s.unit(3, false, 400));  // 1200 bytes: over
    CHECK(b.units().empty());
    CHECK(b.overflows() == 1);
    b.add(s.unit(4, false));  // still waiting for a key frame
    CHECK(b.units().empty());
    b.add(s.unit(5, true));
    for (std::uint64_t p = 6; p <= 8; ++p) b.add(s.unit(p, false));
    CHECK(pts_of(b) == std::vector<std::uint64_t>{5, 6, 7, 8});
    b.add(s.unit(9, false));  // a fifth unit: over
    CHECK(b.units().empty());
    CHECK(b.overflows() == 2);
}
