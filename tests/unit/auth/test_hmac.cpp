#include <catch2/catch.hpp>
#include <string>

#include "auth/hmac.hpp"
#include "auth/secret.hpp"

using namespace gimbal::auth;

namespace {
std::vector<std::uint8_t> bytes(std::string_view s) {
    return {s.begin(), s.end()};
}
}  // namespace

TEST_CASE("HMAC-SHA256 matches RFC 4231") {
    // Test case 2: key "Jefe".
    CHECK(to_hex(hmac_sha256(bytes("Jefe"), "what do ya want for nothing?")) ==
          "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
    // Test case 1: 20 bytes of 0x0b, "Hi There".
    const std::vector<std::uint8_t> key(20, 0x0b);
    CHECK(to_hex(hmac_sha256(key, "Hi There")) ==
          "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
    // Test case 6: a key longer than the block size is hashed first.
    const std::vector<std::uint8_t> long_key(131, 0xaa);
    CHECK(to_hex(hmac_sha256(long_key, "Test Using Larger Than Block-Size Key - Hash Key First")) ==
          "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54");
}

TEST_CASE("hex text converts both ways and rejects what is not hex") {
    const std::vector<std::uint8_t> b{0x00, 0x7f, 0xab, 0xff};
    CHECK(to_hex(b) == "007fabff");
    CHECK(from_hex("007FabFF") == b);
    CHECK_FALSE(from_hex("abc"));
    CHECK_FALSE(from_hex("zz"));
    CHECK(from_hex("")->empty());
}

TEST_CASE("MACs compare in constant time and by length") {
    const auto a = hmac_sha256(bytes("k"), "x");
    auto b = a;
    CHECK(equal_constant_time(a, b));
    b[31] ^= 1;
    CHECK_FALSE(equal_constant_time(a, b));
    CHECK_FALSE(equal_constant_time(std::span(a).first(16), a));
}

TEST_CASE("secret files: 64+ hex characters, white space ignored") {
    const std::string hex64(64, 'a');
    auto ok = parse_secret("  " + hex64 + "\n");
    REQUIRE(std::holds_alternative<std::vector<std::uint8_t>>(ok));
    CHECK(std::get<std::vector<std::uint8_t>>(ok).size() == 32);
    auto short_one = parse_secret(std::string(62, 'a'));
    REQUIRE(std::holds_alternative<std::string>(short_one));
    CHECK_THAT(std::get<std::string>(short_one), Catch::Contains("too short"));
    CHECK(std::holds_alternative<std::string>(parse_secret(std::string(64, 'g'))));
    CHECK(std::holds_alternative<std::string>(parse_secret("\n\n")));
}

TEST_CASE("new secrets are 64 hex characters and differ") {
    const auto a = new_secret_text();
    const auto b = new_secret_text();
    CHECK(a.size() == 65);
    CHECK(a != b);
    CHECK(std::holds_alternative<std::vector<std::uint8_t>>(parse_secret(a)));
}
