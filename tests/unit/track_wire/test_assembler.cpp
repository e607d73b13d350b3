// Access units larger than one datagram, cut into pieces and put back together, and every way
// the pieces can arrive wrong.
#include <catch2/catch.hpp>
#include <numeric>

#include "track/wire/assembler.hpp"
#include "track/wire/codec.hpp"

using namespace gimbal::track::wire;
using Bytes = std::vector<std::uint8_t>;

namespace {

Bytes unit_bytes(std::size_t n, std::uint8_t seed) {
    Bytes b(n);
    std::iota(b.begin(), b.end(), seed);
    return b;
}

AccessUnit piece_of(const Bytes& datagram) {
    const auto d = decode(datagram);
    REQUIRE(d.message);
    return std::get<AccessUnit>(*d.message);
}

}  // namespace

TEST_CASE("assembler: a unit in pieces comes back whole", "[track][wire]") {
    const Bytes unit = unit_bytes(300000, 7);
    const auto datagrams = encode_access_unit(9000, true, Codec::h265, unit, 131072);
    REQUIRE(datagrams.size() == 3);
    for (const auto& d : datagrams) CHECK(d.size() <= 131072 + max_header_bytes);
    AccessUnitAssembler a;
    CHECK_FALSE(a.add(piece_of(datagrams[0])));
    CHECK(a.assembling());
    CHECK_FALSE(a.add(piece_of(datagrams[1])));
    const auto whole = a.add(piece_of(datagrams[2]));
    REQUIRE(whole);
    CHECK(whole->pts_90k == 9000);
    CHECK(whole->key);
    CHECK(whole->codec == Codec::h265);
    CHECK(Bytes(whole->bytes.begin(), whole->bytes.end()) == unit);
    CHECK(a.dropped() == 0);
    CHECK_FALSE(a.assembling());
}

TEST_CASE("assembler: a unit in one piece is not copied", "[track][wire]") {
    const Bytes unit = unit_bytes(1000, 1);
    const auto datagrams = encode_access_unit(1, false, Codec::h264, unit, 131072);
    REQUIRE(datagrams.size() == 1);
    const AccessUnit piece = piece_of(datagrams[0]);
    AccessUnitAssembler a;
    const auto whole = a.add(piece);
    REQUIRE(whole);
    CHECK(whole->bytes.data() == piece.bytes.data());
    CHECK(whole->bytes.size() == 1000);
    // An empty unit too.
    const auto empty = encode_access_unit(2, false, Codec::h264, {}, 100);
    REQUIRE(empty.size() == 1);
    CHECK(a.add(piece_of(empty[0]))->bytes.empty());
}

TEST_CASE("assembler: pieces out of order drop the unit, counted", "[track][wire]") {
    const Bytes first = unit_bytes(250, 0), second = unit_bytes(250, 100);
    const auto a_pieces = encode_access_unit(100, false, Codec::h264, first, 100);
    const auto b_pieces = encode_access_unit(200, false, Codec::h264, second, 100);
    REQUIRE(a_pieces.size() == 3);
    AccessUnitAssembler a;
    // A piece lost: the next unit starts, the broken one is dropped.
    a.add(piece_of(a_pieces[0]));
    const auto b0 = a.add(piece_of(b_pieces[0]));
    CHECK_FALSE(b0);
    CHECK(a.dropped() == 1);
    a.add(piece_of(b_pieces[1]));
    const auto b = a.add(piece_of(b_pieces[2]));
    REQUIRE(b);
    CHECK(Bytes(b->bytes.begin(), b->bytes.end()) == second);
    // The middle of a unit without its start: dropped.
    CHECK_FALSE(a.add(piece_of(a_pieces[1])));
    CHECK(a.dropped() == 2);
    // A repeated piece (an overlap) drops the unit.
    a.add(piece_of(a_pieces[0]));
    CHECK_FALSE(a.add(piece_of(a_pieces[0])));  // restarts it: the old one dropped
    CHECK(a.dropped() == 3);
    a.add(piece_of(a_pieces[1]));
    CHECK(a.add(piece_of(a_pieces[2])));
}

TEST_CASE("assembler: nothing to send for a unit beyond the cap", "[track][wire]") {
    const Bytes huge(max_access_unit_bytes + 1, 0);
    CHECK(encode_access_unit(0, true, Codec::h264, huge, 131072).empty());
    CHECK(encode_access_unit(0, true, Codec::h264, unit_bytes(10, 0), 0).empty());
}
