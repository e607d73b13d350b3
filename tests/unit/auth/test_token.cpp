// command.token is compared in constant time (contract section 14): equal strings match,
// anything else - another length, a prefix, one bit off - does not.
#include <catch2/catch.hpp>

#include <string>

#include "auth/token.hpp"

using gimbal::auth::token_matches;

TEST_CASE("token_matches: equal only when equal") {
    CHECK(token_matches("s3cret-token", "s3cret-token"));
    CHECK(token_matches("", ""));
    CHECK_FALSE(token_matches("s3cret-token", "s3cret-tokem"));
    CHECK_FALSE(token_matches("s3cret", "s3cret-token"));  // a prefix
    CHECK_FALSE(token_matches("s3cret-token-", "s3cret-token"));
    CHECK_FALSE(token_matches("", "s3cret-token"));
    std::string flipped = "s3cret-token";
    flipped[0] = static_cast<char>(flipped[0] ^ 0x01);
    CHECK_FALSE(token_matches(flipped, "s3cret-token"));
    // Binary-safe: an embedded NUL is part of the token.
    CHECK_FALSE(token_matches(std::string("ab\0c", 4), std::string("ab\0d", 4)));
    CHECK(token_matches(std::string("ab\0c", 4), std::string("ab\0c", 4)));
}
