// The pcapng writer against golden bytes built by hand from the pcapng spec
// (draft-ietf-opsawg-pcapng: SHB 4.1, IDB 4.2, EPB 4.3) and Wireshark's exported-PDU TLVs.
#include <catch2/catch.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "record/pcapng_writer.hpp"

using namespace gimbal::record;

namespace {

std::uint32_t u32le(const Bytes& b, std::size_t at) {
    return static_cast<std::uint32_t>(b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
                                      (static_cast<std::uint32_t>(b[at + 3]) << 24));
}

// Walks the blocks: each starts 4-aligned, both length fields agree, the last ends the buffer.
std::vector<std::uint32_t> block_types(const Bytes& b) {
    std::vector<std::uint32_t> types;
    std::size_t at = 0;
    while (at < b.size()) {
        REQUIRE(at % 4 == 0);
        REQUIRE(b.size() - at >= 12);
        const std::uint32_t len = u32le(b, at + 4);
        REQUIRE(len % 4 == 0);
        REQUIRE(len >= 12);
        REQUIRE(at + len <= b.size());
        REQUIRE(u32le(b, at + len - 4) == len);
        types.push_back(u32le(b, at));
        at += len;
    }
    REQUIRE(at == b.size());
    return types;
}

}  // namespace

TEST_CASE("section header block: golden bytes") {
    Bytes out;
    append_section_header(out, "gimbald 1");
    // clang-format off
    const Bytes golden = {
        0x0A, 0x0D, 0x0D, 0x0A,  // block type
        0x30, 0x00, 0x00, 0x00,  // total length 48
        0x4D, 0x3C, 0x2B, 0x1A,  // byte-order magic
        0x01, 0x00, 0x00, 0x00,  // version 1.0
        0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,  // section length -1
        0x04, 0x00, 0x09, 0x00,  // shb_userappl, 9 bytes
        'g', 'i', 'm', 'b', 'a', 'l', 'd', ' ', '1', 0x00, 0x00, 0x00,
        0x00, 0x00, 0x00, 0x00,  // opt_endofopt
        0x30, 0x00, 0x00, 0x00,  // total length again
    };
    // clang-format on
    CHECK(out == golden);
    CHECK(block_length(out) == 48);
}

TEST_CASE("interface description block: golden bytes") {
    Bytes out;
    append_interface(out, {"gimbal:a", "orion sim"});
    // clang-format off
    const Bytes golden = {
        0x01, 0x00, 0x00, 0x00,  // IDB
        0x3C, 0x00, 0x00, 0x00,  // 60
        0xFC, 0x00, 0x00, 0x00,  // linktype 252, reserved
        0x00, 0x00, 0x00, 0x00,  // snaplen 0
        0x02, 0x00, 0x08, 0x00,  // if_name, 8 bytes
        'g', 'i', 'm', 'b', 'a', 'l', ':', 'a',
        0x03, 0x00, 0x09, 0x00,  // if_description, 9 bytes
        'o', 'r', 'i', 'o', 'n', ' ', 's', 'i', 'm', 0x00, 0x00, 0x00,
        0x09, 0x00, 0x01, 0x00, 0x06, 0x00, 0x00, 0x00,  // if_tsresol = 6 (microseconds)
        0x00, 0x00, 0x00, 0x00,  // opt_endofopt
        0x3C, 0x00, 0x00, 0x00,
    };
    // clang-format on
    CHECK(out == golden);
}

TEST_CASE("enhanced packet block with exported-PDU TLVs: golden bytes") {
    const Bytes pdu = {0xD0, 0x0D, 0x05, 0x00, 0xC1, 0xC2};
    Bytes out;
    append_packet(out, {1, 0x00062A1B3C4D5E6Full, Direction::outbound, "orion", pdu});
    // clang-format off
    const Bytes golden = {
        0x06, 0x00, 0x00, 0x00,  // EPB
        0x44, 0x00, 0x00, 0x00,  // 68
        0x01, 0x00, 0x00, 0x00,  // interface 1
        0x1B, 0x2A, 0x06, 0x00,  // timestamp high
        0x6F, 0x5E, 0x4D, 0x3C,  // timestamp low
        0x16, 0x00, 0x00, 0x00,  // captured 22
        0x16, 0x00, 0x00, 0x00,  // original 22
        0x00, 0x0C, 0x00, 0x08,  // EXP_PDU_TAG_DISSECTOR_NAME (12), 8 bytes, big-endian
        'o', 'r', 'i', 'o', 'n', 0x00, 0x00, 0x00,
        0x00, 0x00, 0x00, 0x00,  // EXP_PDU_TAG_END_OF_OPT
        0xD0, 0x0D, 0x05, 0x00, 0xC1, 0xC2, 0x00, 0x00,  // PDU + padding
        0x02, 0x00, 0x04, 0x00, 0x02, 0x00, 0x00, 0x00,  // epb_flags = 2 (outbound)
        0x00, 0x00, 0x00, 0x00,  // opt_endofopt
        0x44, 0x00, 0x00, 0x00,
    };
    // clang-format on
    CHECK(out == golden);
    CHECK(packet_block_size("orion", pdu.size()) == golden.size());
}

TEST_CASE("inbound direction is epb_flags 1") {
    const Bytes pdu = {'{', '}'};
    Bytes out;
    append_packet(out, {2, 1, Direction::inbound, "gimbald-json", pdu});
    // 8 + 20 + padded(4 + 12 + 4 + 2) + flags option 8 + end 4 + length 4
    REQUIRE(out.size() == 8 + 20 + 24 + 8 + 4 + 4);
    CHECK(u32le(out, out.size() - 16) == 0x00040002);  // code 2, length 4
    CHECK(u32le(out, out.size() - 12) == 1);
}

TEST_CASE("every block is 4-byte aligned with matching lengths, for any PDU length") {
    const std::vector<Interface> interfaces = {
        {"gimbal:main", "orion tcp 127.0.0.1:8747"}, {"mavlink", "udp"}, {"json", ""}};
    Bytes file = file_header("gimbald 0.1.0", interfaces);
    std::size_t expected_size = file.size();
    for (const std::string dissector : {"orion", "viewpro", "mavlink", "gimbald-json", "data", ""})
        for (std::size_t n = 0; n < 13; ++n) {
            const Bytes pdu(n, 0xAB);
            append_packet(
                file, {static_cast<std::uint32_t>(n % 3), n, Direction::inbound, dissector, pdu});
            expected_size += packet_block_size(dissector, n);
            // The captured length counts the TLVs and the PDU, not the padding.
            const std::size_t block_start = expected_size - packet_block_size(dissector, n);
            CHECK(u32le(file, block_start + 20) == 4 + padded4(dissector.size()) + 4 + n);
        }
    CHECK(file.size() == expected_size);
    const auto types = block_types(file);
    REQUIRE(types.size() == 1 + 3 + 6 * 13);
    CHECK(types[0] == shb_block_type);
    CHECK(types[1] == idb_block_type);
    CHECK(types[3] == idb_block_type);
    CHECK(types[4] == epb_block_type);
}

TEST_CASE("block_length reads the length field, 0 when too short") {
    Bytes out;
    append_interface(out, {"json", "gimbald JSON requests and replies"});
    CHECK(block_length(out) == out.size());
    CHECK(block_length(std::span(out).first(7)) == 0);
}
