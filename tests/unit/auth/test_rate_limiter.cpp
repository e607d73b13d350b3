#include <catch2/catch.hpp>

#include "auth/rate_limiter.hpp"

using gimbal::auth::RateLimiter;
using D = RateLimiter::Decision;

TEST_CASE("a burst passes, then the rate; one refusal reply per second") {
    RateLimiter limiter(10, 5);
    for (int i = 0; i < 5; ++i) CHECK(limiter.admit("a", 0.0) == D::admit);
    CHECK(limiter.admit("a", 0.0) == D::limited_reply);
    CHECK(limiter.admit("a", 0.01) == D::limited_silent);
    CHECK(limiter.admit("a", 0.05) == D::limited_silent);
    // 0.1 s at 10 Hz refills one token.
    CHECK(limiter.admit("a", 0.15) == D::admit);
    CHECK(limiter.admit("a", 0.16) == D::limited_silent);
    CHECK(limiter.admit("a", 1.0) == D::admit);  // refilled to the burst
    for (int i = 0; i < 4; ++i) CHECK(limiter.admit("a", 1.0) == D::admit);
    CHECK(limiter.admit("a", 1.0) == D::limited_reply);  // a second after the last reply
    CHECK(limiter.admit("a", 1.0) == D::limited_silent);
}

TEST_CASE("one source's flood does not touch another's bucket") {
    RateLimiter limiter(10, 2);
    for (int i = 0; i < 100; ++i) limiter.admit("flood", 0.0);
    CHECK(limiter.admit("quiet", 0.0) == D::admit);
    CHECK(limiter.admit("quiet", 0.0) == D::admit);
}

TEST_CASE("the table of sources is bounded") {
    RateLimiter limiter(1, 1, 8);
    for (int i = 0; i < 1000; ++i) limiter.admit("s" + std::to_string(i), i * 0.001);
    CHECK(limiter.sources() <= 8);
    // A source evicted from a full table starts with a full bucket, never an empty one.
    CHECK(limiter.admit("s0", 1.0) == D::admit);
}
