// DateTime: ISO-8601 text and Unix seconds.
#include <catch2/catch.hpp>

#include "protocols/viewpro/codec/time.hpp"

using namespace gimbal::viewpro;

TEST_CASE("DateTime prints as ISO-8601 UTC", "[viewpro][time]") {
    CHECK(to_iso8601(DateTime{2021, 8, 7, 17, 27, 58}) == "2021-08-07T17:27:58Z");
    CHECK(to_iso8601(DateTime{}) == "2000-01-01T00:00:00Z");
}

TEST_CASE("ISO-8601 parses, with or without a fraction", "[viewpro][time]") {
    CHECK(parse_iso8601("2026-11-21T06:41:50.123Z") == DateTime{2026, 11, 21, 6, 41, 50});
    CHECK(parse_iso8601("2026-11-21T06:41:50Z") == DateTime{2026, 11, 21, 6, 41, 50});
    CHECK(parse_iso8601("2024-02-29T23:59:59+00:00") == DateTime{2024, 2, 29, 23, 59, 59});
    CHECK_FALSE(parse_iso8601("2023-02-29T00:00:00Z"));  // not a leap year
    CHECK_FALSE(parse_iso8601("2026-13-01T00:00:00Z"));
    CHECK_FALSE(parse_iso8601("2026-11-21T24:00:00Z"));
    CHECK_FALSE(parse_iso8601("2026-11-21T06:41:50"));  // no zone
    CHECK_FALSE(parse_iso8601("2026-11-21T06:41:50+01:00"));
    CHECK_FALSE(parse_iso8601("2026-11-21 06:41:50Z"));
    CHECK_FALSE(parse_iso8601("2026-11-21T06:41:50.Z"));
    CHECK_FALSE(parse_iso8601("yesterday"));
    CHECK_FALSE(parse_iso8601(""));
}

TEST_CASE("Unix seconds convert both ways", "[viewpro][time]") {
    CHECK(from_unix_seconds(0) == DateTime{1970, 1, 1, 0, 0, 0});
    CHECK(from_unix_seconds(1735689600.0) == DateTime{2025, 1, 1, 0, 0, 0});
    CHECK(from_unix_seconds(1709251199.9) == DateTime{2024, 2, 29, 23, 59, 59});
    CHECK(to_unix_seconds(DateTime{2025, 1, 1, 0, 0, 0}) == 1735689600.0);
    CHECK(to_unix_seconds(DateTime{2024, 2, 29, 23, 59, 59}) == 1709251199.0);
    for (double t = 946684800.0; t < 4102444800.0; t += 86400.0 * 37 + 3671.0)
        CHECK(to_unix_seconds(from_unix_seconds(t)) == t);
}
