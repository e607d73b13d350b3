// Transport packet header, PSI sections and PES headers against bytes written by hand from
// ISO/IEC 13818-1, and the CRC against its published check value.
#include <catch2/catch.hpp>
#include <string_view>

#include "ts_builder.hpp"
#include "video/codec.hpp"
#include "video/crc32.hpp"
#include "video/pes.hpp"
#include "video/psi.hpp"
#include "video/ts_packet.hpp"

namespace v = gimbal::video;
using gimbal::test::Bytes;

TEST_CASE("CRC-32/MPEG-2: check value and PSI sections", "[video][psi]") {
    // The catalogue check value of CRC-32/MPEG-2 over the ASCII digits 1..9.
    const std::string_view digits = "123456789";
    const Bytes ascii(digits.begin(), digits.end());
    CHECK(v::crc32_mpeg2(ascii) == 0x0376E6E7u);
    // A PAT: TS id 1, version 0, program 1 -> PMT PID 0x1000 (Table 2-30), CRC included.
    const Bytes pat = {0x00, 0xB0, 0x0D, 0x00, 0x01, 0xC1, 0x00, 0x00,
                       0x00, 0x01, 0xF0, 0x00, 0x2A, 0xB1, 0x04, 0xB2};
    CHECK(v::crc32_mpeg2(pat) == 0);
    CHECK(gimbal::test::pat(1, 0x1000) == pat);
}

TEST_CASE("PAT: parse, build, and what is refused", "[video][psi]") {
    const Bytes s = gimbal::test::pat(7, 0x0123, 5, 0x4242);
    const auto pat = v::parse_pat(s);
    REQUIRE(pat);
    CHECK(pat->transport_stream_id == 0x4242);
    CHECK(pat->version == 5);
    REQUIRE(pat->programs.size() == 1);
    CHECK(pat->programs[0].program_number == 7);
    CHECK(pat->programs[0].pmt_pid == 0x0123);
    CHECK(v::build_pat(*pat) == s);

    Bytes bad_crc = s;
    bad_crc.back() ^= 1;
    CHECK_FALSE(v::parse_pat(bad_crc));
    Bytes wrong_table = gimbal::test::section(0x02, 1, 0, {0, 1, 0xF0, 0});
    CHECK_FALSE(v::parse_pat(wrong_table));
    CHECK_FALSE(v::parse_pat(Bytes(s.begin(), s.end() - 1)));
    // current_next_indicator 0: a table announced for later is not used yet.
    Bytes next = s;
    next[5] &= 0xFE;
    const std::uint32_t crc = v::crc32_mpeg2(std::span(next).first(next.size() - 4));
    next[next.size() - 4] = static_cast<std::uint8_t>(crc >> 24);
    next[next.size() - 3] = static_cast<std::uint8_t>(crc >> 16);
    next[next.size() - 2] = static_cast<std::uint8_t>(crc >> 8);
    next[next.size() - 1] = static_cast<std::uint8_t>(crc);
    CHECK_FALSE(v::parse_pat(next));
}

TEST_CASE("PMT: streams, descriptors, KLVA registration and metadata descriptor", "[video][psi]") {
    using gimbal::test::klva_metadata_descriptor;
    using gimbal::test::klva_registration;
    const Bytes s = gimbal::test::pmt(1, 0x100,
                                      {{0x1B, 0x100, {}},
                                       {0x06, 0x101, klva_registration},
                                       {0x15, 0x102, klva_metadata_descriptor}},
                                      3, {0x25, 0x00});
    const auto pmt = v::parse_pmt(s);
    REQUIRE(pmt);
    CHECK(pmt->program_number == 1);
    CHECK(pmt->version == 3);
    CHECK(pmt->pcr_pid == 0x100);
    CHECK(pmt->program_descriptors == Bytes{0x25, 0x00});
    REQUIRE(pmt->streams.size() == 3);
    CHECK(pmt->streams[0].stream_type == v::stream_type::h264);
    CHECK(pmt->streams[1].pid == 0x101);
    CHECK(v::registration_format(pmt->streams[1].descriptors) == v::format_klva);
    CHECK_FALSE(v::registration_format(pmt->streams[0].descriptors));
    CHECK(v::has_klva_metadata_descriptor(pmt->streams[2].descriptors));
    CHECK_FALSE(v::has_klva_metadata_descriptor(pmt->streams[1].descriptors));
    CHECK(v::build_pmt(*pmt) == s);
    // An ES_info_length running past the section is refused.
    Bytes cut =
        gimbal::test::section(0x02, 1, 0, {0xE1, 0x00, 0xF0, 0x00, 0x1B, 0xE1, 0x00, 0xF0, 0x09});
    CHECK_FALSE(v::parse_pmt(cut));
}

namespace {
gimbal::test::PacketOptions t_opts() {
    return gimbal::test::PacketOptions().start().counter(9).pcr(0x1'2345'6789).rai();
}
}  // namespace

TEST_CASE("Transport packet header and adaptation field (Tables 2-2, 2-6)", "[video][ts]") {
    Bytes p = gimbal::test::packet(0x0100, Bytes(100, 0xAB), t_opts());
    REQUIRE(p.size() == 188);
    CHECK(p[0] == 0x47);
    CHECK(p[1] == 0x41);  // payload_unit_start, PID high bits 1
    CHECK(p[3] == 0x39);  // adaptation + payload, CC 9
    const auto t = v::parse_ts_packet(p);
    REQUIRE(t);
    CHECK(t->pid == 0x100);
    CHECK(t->payload_unit_start);
    CHECK(t->continuity_counter == 9);
    CHECK(t->random_access);
    CHECK_FALSE(t->discontinuity);
    REQUIRE(t->pcr);
    CHECK(*t->pcr == 0x1'2345'6789ull * 300);
    CHECK(t->payload.size() == 100);
    CHECK(t->payload[0] == 0xAB);

    p[4] = 184;  // adaptation_field_length past the packet
    CHECK_FALSE(v::parse_ts_packet(p));
    CHECK_FALSE(v::parse_ts_packet(std::span(p).first(187)));
}

TEST_CASE("PES header: PTS/DTS coding (2.4.3.7) both ways", "[video][pes]") {
    // PTS 900000 (10 s): '0010', 000, 1 | 000000000011011 1 | 011101110100000 1.
    const Bytes golden = {0x00, 0x00, 0x01, 0xE0, 0x00, 0x00, 0x84,
                          0x80, 0x05, 0x21, 0x00, 0x37, 0x77, 0x41};
    Bytes out;
    v::write_pes_header(out, v::stream_id::video, 0, 900000, std::nullopt, true);
    CHECK(out == golden);
    const auto h = v::parse_pes_header(golden);
    REQUIRE(h);
    CHECK(h->stream_id == 0xE0);
    CHECK(h->packet_length == 0);
    CHECK(h->data_alignment);
    CHECK(h->pts == 900000u);
    CHECK_FALSE(h->dts);
    CHECK(h->header_size == 14);

    // The largest 33-bit values, PTS and DTS, bounded length.
    const std::uint64_t top = v::pts_modulus - 1;
    out.clear();
    v::write_pes_header(out, v::stream_id::private_stream_1, 20, top, top - 3003, true);
    const auto h2 = v::parse_pes_header(out);
    REQUIRE(h2);
    CHECK(h2->pts == top);
    CHECK(h2->dts == top - 3003);
    CHECK(h2->packet_length == 20 + 3 + 10);
    const Bytes built = gimbal::test::pes(0xBD, Bytes(20, 0), top, top - 3003);
    CHECK(out == Bytes(built.begin(), built.begin() + 19));

    CHECK_FALSE(v::parse_pes_header(Bytes{0x00, 0x00, 0x02, 0xE0, 0, 0}));
    CHECK_FALSE(v::parse_pes_header(Bytes{0x00, 0x00, 0x01, 0xE0, 0, 0, 0x84, 0x80, 0x05, 0x21}));
}

TEST_CASE("Section assembly: spanning packets, several per packet, empty sections",
          "[video][psi]") {
    const Bytes a = gimbal::test::pat(1, 0x100);
    const Bytes b = gimbal::test::pat(2, 0x200);
    std::vector<Bytes> got;
    v::SectionAssembler asm_;
    auto on = [&](std::span<const std::uint8_t> s) { got.emplace_back(s.begin(), s.end()); };
    // Two sections in one payload, the second cut and finished by the next packet.
    Bytes first = {0x00};
    first.insert(first.end(), a.begin(), a.end());
    first.insert(first.end(), b.begin(), b.begin() + 5);
    asm_.push(first, true, on);
    asm_.push(Bytes(b.begin() + 5, b.end()), false, on);
    REQUIRE(got.size() == 2);
    CHECK(got[0] == a);
    CHECK(got[1] == b);
    // A section_length of 0 (found by the fuzzer: it used to spin) ends the payload.
    asm_.push(Bytes{0x00, 0x00, 0xB0, 0x00, 0x00, 0x00}, true, on);
    CHECK(got.size() == 2);
    // A pointer_field past the payload is dropped.
    asm_.push(Bytes{0x10, 0x00}, true, on);
    CHECK(got.size() == 2);
}
