// BER lengths and BER-OID tags (SMPTE 336 / ST 0601 section 6): minimal encoding, every
// valid form decoded, over-long and truncated forms refused.
#include <catch2/catch.hpp>
#include <limits>

#include "klv/ber.hpp"

using namespace gimbal::klv;

namespace {

Bytes length_bytes(std::uint64_t n) {
    Bytes out;
    append_ber_length(out, n);
    return out;
}

Bytes oid_bytes(std::uint64_t n) {
    Bytes out;
    append_ber_oid(out, n);
    return out;
}

}  // namespace

TEST_CASE("BER length: minimal short and long forms") {
    CHECK(length_bytes(0) == Bytes{0x00});
    CHECK(length_bytes(127) == Bytes{0x7F});
    CHECK(length_bytes(128) == Bytes{0x81, 0x80});
    CHECK(length_bytes(255) == Bytes{0x81, 0xFF});
    CHECK(length_bytes(256) == Bytes{0x82, 0x01, 0x00});
    CHECK(length_bytes(65535) == Bytes{0x82, 0xFF, 0xFF});
    CHECK(length_bytes(65536) == Bytes{0x83, 0x01, 0x00, 0x00});
    CHECK(length_bytes(std::numeric_limits<std::uint64_t>::max()) ==
          Bytes{0x88, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF});
    for (const std::uint64_t n : {0ull, 1ull, 127ull, 128ull, 300ull, 70000ull, 1ull << 40}) {
        const Bytes b = length_bytes(n);
        CHECK(ber_length_size(n) == b.size());
        const BerRead r = read_ber_length(b);
        CHECK(r.status == BerStatus::ok);
        CHECK(r.value == n);
        CHECK(r.size == b.size());
    }
}

TEST_CASE("BER length: any valid long form is read") {
    // SMPTE 336 writers often use a fixed 4-byte long form; it is valid BER.
    const Bytes four{0x84, 0x00, 0x00, 0x00, 0x05, 0xAA};
    const BerRead r = read_ber_length(four);
    CHECK(r.status == BerStatus::ok);
    CHECK(r.value == 5);
    CHECK(r.size == 5);
    const Bytes padded{0x81, 0x05};
    CHECK(read_ber_length(padded).value == 5);
    const Bytes eight{0x88, 0, 0, 0, 0, 0, 0, 0x01, 0x00};
    CHECK(read_ber_length(eight).value == 256);
}

TEST_CASE("BER length: indefinite, over-long and truncated forms are refused") {
    CHECK(read_ber_length(Bytes{0x80}).status == BerStatus::invalid);  // indefinite
    CHECK(read_ber_length(Bytes{0x89, 0, 0, 0, 0, 0, 0, 0, 0, 1}).status == BerStatus::invalid);
    CHECK(read_ber_length(Bytes{0xFF}).status == BerStatus::invalid);
    CHECK(read_ber_length(Bytes{}).status == BerStatus::truncated);
    CHECK(read_ber_length(Bytes{0x82, 0x01}).status == BerStatus::truncated);
    CHECK(read_ber_length(Bytes{0x84, 0x00, 0x00, 0x00}).status == BerStatus::truncated);
}

TEST_CASE("BER-OID: tags above 127 take two or more bytes") {
    CHECK(oid_bytes(0) == Bytes{0x00});
    CHECK(oid_bytes(1) == Bytes{0x01});
    CHECK(oid_bytes(127) == Bytes{0x7F});
    CHECK(oid_bytes(128) == Bytes{0x81, 0x00});
    CHECK(oid_bytes(143) == Bytes{0x81, 0x0F});  // ST 0601's last tag
    CHECK(oid_bytes(16383) == Bytes{0xFF, 0x7F});
    CHECK(oid_bytes(16384) == Bytes{0x81, 0x80, 0x00});
    CHECK(oid_bytes(std::numeric_limits<std::uint64_t>::max()) ==
          Bytes{0x81, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x7F});
    const std::vector<std::uint64_t> values{
        0, 127, 128, 143, 16384, std::uint64_t{1} << 35, std::numeric_limits<std::uint64_t>::max()};
    for (const std::uint64_t n : values) {
        const Bytes b = oid_bytes(n);
        CHECK(ber_oid_size(n) == b.size());
        Bytes with_tail = b;
        with_tail.push_back(0x55);  // the next field must not be read
        const BerRead r = read_ber_oid(with_tail);
        CHECK(r.status == BerStatus::ok);
        CHECK(r.value == n);
        CHECK(r.size == b.size());
    }
}

TEST_CASE("BER-OID: padding, overflow and truncation are refused") {
    CHECK(read_ber_oid(Bytes{0x80, 0x01}).status == BerStatus::invalid);  // leading 0x80
    CHECK(read_ber_oid(Bytes{0x82, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x7F}).status ==
          BerStatus::invalid);  // 65 bits
    CHECK(read_ber_oid(Bytes{0x81, 0x81, 0x81, 0x81, 0x81, 0x81, 0x81, 0x81, 0x81, 0x81, 0x01})
              .status == BerStatus::invalid);  // 11 bytes
    CHECK(read_ber_oid(Bytes{}).status == BerStatus::truncated);
    CHECK(read_ber_oid(Bytes{0x81}).status == BerStatus::truncated);
    CHECK(read_ber_oid(Bytes{0x81, 0x80}).status == BerStatus::truncated);
}
