// gimbal::Result, the one result type in its own lowest library (lib/result): the command
// layer's names are the same types, not copies.
#include <catch2/catch.hpp>
#include <type_traits>

#include "command/result.hpp"
#include "result/result.hpp"

using namespace gimbal;

static_assert(std::is_same_v<command::Error, gimbal::Error>);
static_assert(std::is_same_v<command::ErrorCode, gimbal::ErrorCode>);
static_assert(std::is_same_v<command::Result<int>, gimbal::Result<int>>);
static_assert(std::is_same_v<command::Status, gimbal::Result<void>>);

TEST_CASE("gimbal::Result: a value or an Error with a contract code") {
    Result<std::vector<int>> ok = std::vector<int>{1, 2};
    REQUIRE(ok);
    CHECK(ok->size() == 2);
    Result<std::vector<int>> bad{code::unavailable, "no file"};
    REQUIRE_FALSE(bad);
    CHECK(bad.error().code == ErrorCode::unavailable);
    CHECK(to_string(bad.error().code) == "unavailable");
    CHECK(bad.error().code == "unavailable");
    CHECK(parse_error_code("internal") == ErrorCode::internal);
    CHECK_FALSE(parse_error_code("not_a_code"));
    // An Error from one library is the command layer's: no conversion between them.
    const command::Error e = Error{code::bad_request, "x"};
    const Result<void> status = e;
    REQUIRE_FALSE(status.ok());
    CHECK(status.error().message == "x");
    CHECK(nlohmann::json(status.error().code) == "bad_request");
}
