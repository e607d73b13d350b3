// The pcapng reader against hand-built files: a literal golden file, the same content built
// in both byte orders, timestamp resolutions, unknown blocks, several sections, a cut at
// every offset, garbage, and the fuzz target's corpus and crash inputs.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "../../fuzz/record_properties.hpp"
#include "pcapng_builder.hpp"
#include "record/pcapng_reader.hpp"

namespace r = gimbal::record;
using gimbal::test::Builder;
using gimbal::test::Bytes;

namespace {

// SHB (no options), IDB "gimbal:sim" with if_tsresol 6, one EPB: inbound, dissector "orion",
// PDU = the zero-length CROWN_VERSION request D0 0D 28 00 0B CA, at 1764072000.123456 s.
const Bytes golden_le = {
    // Section Header Block, 28 bytes
    0x0A, 0x0D, 0x0D, 0x0A, 0x1C, 0x00, 0x00, 0x00, 0x4D, 0x3C, 0x2B, 0x1A, 0x01, 0x00, 0x00, 0x00,
    0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x1C, 0x00, 0x00, 0x00,
    // Interface Description Block, 48 bytes: link type 252, snaplen 0
    0x01, 0x00, 0x00, 0x00, 0x30, 0x00, 0x00, 0x00, 0xFC, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x02, 0x00, 0x0A, 0x00, 'g', 'i', 'm', 'b', 'a', 'l', ':', 's', 'i', 'm', 0x00, 0x00,  //
    0x09, 0x00, 0x01, 0x00, 0x06, 0x00, 0x00, 0x00,  // if_tsresol 6
    0x00, 0x00, 0x00, 0x00, 0x30, 0x00, 0x00, 0x00,
    // Enhanced Packet Block, 68 bytes
    0x06, 0x00, 0x00, 0x00, 0x44, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // interface 0
    0x6A, 0x44, 0x06, 0x00, 0x40, 0xF2, 0xEC, 0x04,                          // timestamp
    0x16, 0x00, 0x00, 0x00, 0x16, 0x00, 0x00, 0x00,                          // 22 bytes
    0x00, 0x0C, 0x00, 0x05, 'o', 'r', 'i', 'o', 'n', 0x00, 0x00, 0x00,       // dissector
    0x00, 0x00, 0x00, 0x00,                                                  // end of TLVs
    0xD0, 0x0D, 0x28, 0x00, 0x0B, 0xCA, 0x00, 0x00,                          // PDU + pad
    0x02, 0x00, 0x04, 0x00, 0x01, 0x00, 0x00, 0x00,                          // epb_flags
    0x00, 0x00, 0x00, 0x00, 0x44, 0x00, 0x00, 0x00};

const Bytes crown_request = {0xD0, 0x0D, 0x28, 0x00, 0x0B, 0xCA};

std::vector<r::RecordedPacket> read_all(const Bytes& bytes, r::Stop expected_stop) {
    r::PcapngReader reader(bytes);
    std::vector<r::RecordedPacket> packets;
    r::RecordedPacket p;
    while (reader.next(p)) packets.push_back(p);
    CHECK(reader.stop() == expected_stop);
    return packets;
}

Bytes span_bytes(std::span<const std::uint8_t> s) {
    return Bytes(s.begin(), s.end());
}

}  // namespace

TEST_CASE("golden little-endian file", "[record]") {
    r::PcapngReader reader(golden_le);
    r::RecordedPacket p;
    REQUIRE(reader.next(p));
    REQUIRE(reader.interfaces().size() == 1);
    CHECK(reader.interfaces()[0].name == "gimbal:sim");
    CHECK(reader.interfaces()[0].link_type == 252);
    CHECK(reader.interfaces()[0].ticks_per_second == 1'000'000);
    CHECK(p.interface_id == 0);
    CHECK(p.timestamp_us == 1764072000123456);
    CHECK(p.original_length == 22);
    CHECK(p.has_flags);
    CHECK(p.direction == r::RecordedDirection::inbound);
    CHECK(p.dissector == "orion");
    CHECK(p.pdu_error.empty());
    CHECK(span_bytes(p.pdu) == crown_request);
    CHECK_FALSE(reader.next(p));
    CHECK(reader.stop() == r::Stop::end);
    CHECK(reader.offset() == golden_le.size());
    CHECK(reader.sections() == 1);
}

TEST_CASE("the builder writes the golden bytes", "[record]") {
    Builder b(false);
    b.shb()
        .idb("gimbal:sim")
        .epb(0, 1764072000123456, Builder::exported_pdu("orion", crown_request));
    CHECK(b.out == golden_le);
}

TEST_CASE("big-endian sections read the same", "[record]") {
    Builder b(true);
    b.shb()
        .idb("gimbal:sim")
        .idb("json")
        .epb(0, 1764072000123456, Builder::exported_pdu("orion", crown_request), 1);
    const std::string reply = R"({"ok":true})";
    b.epb(1, 1764072000200000,
          Builder::exported_pdu("gimbald-json", Bytes(reply.begin(), reply.end())), 2);
    const auto packets = read_all(b.out, r::Stop::end);
    REQUIRE(packets.size() == 2);
    CHECK(packets[0].timestamp_us == 1764072000123456);
    CHECK(packets[0].dissector == "orion");
    CHECK(span_bytes(packets[0].pdu) == crown_request);
    CHECK(packets[0].direction == r::RecordedDirection::inbound);
    CHECK(packets[1].interface_id == 1);
    CHECK(packets[1].dissector == "gimbald-json");
    CHECK(packets[1].direction == r::RecordedDirection::outbound);
    CHECK(std::string(packets[1].pdu.begin(), packets[1].pdu.end()) == reply);
}

TEST_CASE("timestamp resolutions and offsets", "[record]") {
    SECTION("nanoseconds") {
        Builder b(false);
        b.shb().idb("a", 9).epb(0, 1764072000123456789ULL, Builder::exported_pdu("data", {1}));
        CHECK(read_all(b.out, r::Stop::end).at(0).timestamp_us == 1764072000123456);
    }
    SECTION("power of two: 2^-10 s") {
        Builder b(false);
        b.shb().idb("a", 0x80 | 10).epb(0, 1024 * 5 + 512, Builder::exported_pdu("data", {1}));
        CHECK(read_all(b.out, r::Stop::end).at(0).timestamp_us == 5'500'000);
    }
    SECTION("no if_tsresol means microseconds") {
        Builder b(false);
        b.shb().idb("a", -1).epb(0, 42, Builder::exported_pdu("data", {1}));
        CHECK(read_all(b.out, r::Stop::end).at(0).timestamp_us == 42);
    }
    SECTION("if_tsoffset adds seconds") {
        Builder b(true);
        b.shb().idb("a", 6, 252, 1000).epb(0, 7, Builder::exported_pdu("data", {1}));
        CHECK(read_all(b.out, r::Stop::end).at(0).timestamp_us == 1'000'000'007);
    }
    SECTION("a resolution beyond 64 bits is corrupt") {
        Builder b(false);
        b.shb().idb("a", 20);
        read_all(b.out, r::Stop::corrupt);
    }
}

TEST_CASE("unknown blocks are skipped; a new section starts new interfaces", "[record]") {
    Builder b(false);
    b.shb().idb("first").block(5, Bytes(16, 0xAB)).block(0x40000BAD, Bytes(4, 1));
    b.epb(0, 1, Builder::exported_pdu("orion", crown_request));
    b.shb().idb("second", 6, 1).epb(0, 2, {9, 8, 7}, std::nullopt);
    r::PcapngReader reader(b.out);
    r::RecordedPacket p;
    REQUIRE(reader.next(p));
    CHECK(reader.interfaces().at(0).name == "first");
    CHECK(reader.skipped_blocks() == 2);
    REQUIRE(reader.next(p));
    CHECK(reader.sections() == 2);
    REQUIRE(reader.interfaces().size() == 1);
    CHECK(reader.interfaces()[0].name == "second");
    CHECK(p.dissector.empty());  // link type 1 is not exported PDUs: no TLVs parsed
    CHECK(span_bytes(p.data) == Bytes{9, 8, 7});
    CHECK_FALSE(p.has_flags);
    CHECK(p.direction == r::RecordedDirection::unknown);
    CHECK_FALSE(reader.next(p));
    CHECK(reader.stop() == r::Stop::end);
}

TEST_CASE("malformed exported-PDU tags spoil only their packet", "[record]") {
    Builder b(false);
    b.shb().idb("gimbal:sim");
    b.epb(0, 1, {0x00, 0x0C, 0x00, 0x40, 'o', 'r'});            // tag longer than the packet
    b.epb(0, 2, {0x00, 0x0C, 0x00, 0x04, 'd', 'a', 't', 'a'});  // no end tag
    b.epb(0, 3, Builder::exported_pdu("viewpro", {0xFE}));
    const auto packets = read_all(b.out, r::Stop::end);
    REQUIRE(packets.size() == 3);
    CHECK_FALSE(packets[0].pdu_error.empty());
    CHECK(packets[0].pdu.empty());
    CHECK_FALSE(packets[1].pdu_error.empty());
    CHECK(packets[2].pdu_error.empty());
    CHECK(packets[2].dissector == "viewpro");
}

TEST_CASE("a cut at every offset reads every complete block and reports the cut", "[record]") {
    Builder b(false);
    b.shb().idb("gimbal:sim").idb("json");
    for (std::uint64_t i = 0; i < 5; ++i)
        b.epb(static_cast<std::uint32_t>(i % 2), 100 + i,
              Builder::exported_pdu(i % 2 ? "gimbald-json" : "orion", Bytes(i + 3, 0x55)));
    const auto& all = b.out;
    for (std::size_t cut = 0; cut <= all.size(); ++cut) {
        CAPTURE(cut);
        const Bytes part(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(cut));
        r::PcapngReader reader(part);
        r::RecordedPacket p;
        std::size_t got = 0;
        while (reader.next(p)) {
            CHECK(p.timestamp_us == static_cast<std::int64_t>(100 + got));
            ++got;
        }
        // Packets are blocks 3.. ; count those that end at or before the cut.
        std::size_t complete = 0;
        bool at_boundary = cut == all.size();
        for (std::size_t k = 0; k < b.boundaries.size(); ++k) {
            const std::size_t end = k + 1 < b.boundaries.size() ? b.boundaries[k + 1] : all.size();
            if (k >= 3 && end <= cut) ++complete;
            if (b.boundaries[k] == cut) at_boundary = true;
        }
        CHECK(got == complete);
        if (at_boundary && cut > 0) {
            CHECK(reader.stop() == r::Stop::end);
        } else {
            CHECK(reader.stop() == r::Stop::truncated);
            CHECK_FALSE(reader.stop_message().empty());
        }
        CHECK(gimbal::fuzz::check_record_reader(part) == "");
    }
}

TEST_CASE("garbage is refused without reading past the input", "[record]") {
    SECTION("not pcapng") {
        const std::string text = "this is not a capture file at all.";
        r::PcapngReader reader(
            std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
        r::RecordedPacket p;
        CHECK_FALSE(reader.next(p));
        CHECK(reader.stop() == r::Stop::corrupt);
        CHECK(reader.stop_message().find("not a pcapng file") != std::string::npos);
    }
    SECTION("a bad trailing length stops after the good packets") {
        Builder b(false);
        b.shb().idb("g").epb(0, 1, Builder::exported_pdu("orion", crown_request));
        const std::size_t bad = b.out.size();
        b.epb(0, 2, Builder::exported_pdu("orion", crown_request));
        b.out[b.out.size() - 4] ^= 0x40;
        r::PcapngReader reader(b.out);
        r::RecordedPacket p;
        CHECK(reader.next(p));
        CHECK_FALSE(reader.next(p));
        CHECK(reader.stop() == r::Stop::corrupt);
        CHECK(reader.offset() == bad);
    }
    SECTION("a packet naming a missing interface") {
        Builder b(false);
        b.shb().idb("g").epb(3, 1, {});
        read_all(b.out, r::Stop::corrupt);
    }
    SECTION("bad byte-order magic") {
        Bytes bytes = golden_le;
        bytes[8] = 0x00;
        read_all(bytes, r::Stop::corrupt);
    }
    SECTION("random bytes, and random damage to a good file") {
        std::mt19937 random(12345);
        for (int round = 0; round < 2000; ++round) {
            Bytes bytes;
            if (round % 2) {
                bytes.resize(random() % 200);
                for (auto& x : bytes) x = static_cast<std::uint8_t>(random());
            } else {
                bytes = golden_le;
                for (int k = 0; k < 3; ++k)
                    bytes[random() % bytes.size()] = static_cast<std::uint8_t>(random());
            }
            CAPTURE(round);
            CHECK(gimbal::fuzz::check_record_reader(bytes) == "");
        }
    }
}

TEST_CASE("fuzz corpus and crash inputs: record reader", "[record][fuzz]") {
    namespace fs = std::filesystem;
    const fs::path fuzz_dir = fs::path(__FILE__).parent_path() / ".." / ".." / "fuzz";
    std::size_t files = 0;
    for (const char* kind : {"corpus", "regressions"}) {
        const fs::path dir = fuzz_dir / kind / "record_reader";
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir)) {
            if (!entry.is_regular_file()) continue;
            std::ifstream in(entry.path(), std::ios::binary);
            const Bytes bytes(std::istreambuf_iterator<char>(in), {});
            CAPTURE(entry.path().filename().string());
            CHECK(gimbal::fuzz::check_record_reader(bytes) == "");
            ++files;
        }
    }
    CHECK(files > 0);
}
