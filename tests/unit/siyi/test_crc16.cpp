// The CRC is pinned before anything is built on it: the catalogued check value of
// CRC-16/XMODEM, and every example frame of SIYI's documents (vectors.hpp).
#include <catch2/catch.hpp>
#include <random>

#include "protocols/siyi/codec/crc16.hpp"
#include "vectors.hpp"

using namespace gimbal::siyi;
using namespace siyi_test;

namespace {

// Bit by bit, straight from the polynomial: an independent check of the table.
std::uint16_t crc_bitwise(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
    for (const std::uint8_t b : bytes) {
        crc = static_cast<std::uint16_t>(crc ^ (b << 8));
        for (int i = 0; i < 8; ++i)
            crc = static_cast<std::uint16_t>((crc & 0x8000) ? (crc << 1) ^ 0x1021 : crc << 1);
    }
    return crc;
}

std::uint16_t trailer(const Bytes& frame) {
    return static_cast<std::uint16_t>(frame[frame.size() - 2] | frame.back() << 8);
}

std::span<const std::uint8_t> covered(const Bytes& frame) {
    return std::span(frame).first(frame.size() - 2);
}

}  // namespace

TEST_CASE("crc16 is CRC-16/XMODEM", "[siyi][crc]") {
    const std::string_view check = "123456789";
    const auto* p = reinterpret_cast<const std::uint8_t*>(check.data());
    CHECK(crc16({p, check.size()}) == 0x31C3);  // the catalogue's check value
    CHECK(crc16({}) == 0x0000);
}

TEST_CASE("crc16 matches every example frame of SIYI's documents", "[siyi][crc][golden]") {
    std::vector<Golden> all = sdk_requests();
    all.insert(all.end(), sdk_undeclared().begin(), sdk_undeclared().end());
    for (const Golden& g : all) {
        CAPTURE(g.what, g.source);
        CHECK(crc16(covered(g.bytes)) == trailer(g.bytes));
    }
    for (const Bytes* reply :
         {&mk15_hardware_id_reply, &captured_attitude_reply, &captured_attitude_reply2})
        CHECK(crc16(covered(*reply)) == trailer(*reply));
}

TEST_CASE("the example frames rule out the other common CRC-16 variants", "[siyi][crc]") {
    const Bytes& centering = sdk_requests()[10].bytes;  // one-key centering, D1 12
    REQUIRE(trailer(centering) == 0x12D1);
    CHECK(crc_bitwise(covered(centering), 0xFFFF) != 0x12D1);  // CRC-16/CCITT-FALSE
    CHECK(crc_bitwise(covered(centering), 0x1D0F) != 0x12D1);  // CRC-16/AUG-CCITT
    CHECK(crc_bitwise(covered(centering), 0x0000) == 0x12D1);
}

TEST_CASE("crc16's table agrees with the polynomial bit by bit", "[siyi][crc]") {
    std::mt19937 rng(7);
    for (int n = 0; n < 200; ++n) {
        Bytes data(rng() % 300);
        for (auto& b : data) b = static_cast<std::uint8_t>(rng());
        const auto init = static_cast<std::uint16_t>(rng());
        REQUIRE(crc16(data, init) == crc_bitwise(data, init));
    }
}
