// The request limits of contract section 14, checked on the raw text before anything is
// parsed: 8192 bytes, 32 levels of nesting; a refused request echoes nothing.
#include <catch2/catch.hpp>

#include <string>

#include "command/envelope.hpp"
#include "command/request.hpp"
#include "command/request_limits.hpp"

namespace command = gimbal::command;

namespace {

// A ping of exactly `size` bytes with id 9.
std::string padded(std::size_t size) {
    const std::string head = R"({"cmd":"ping","id":9,"pad":")";
    return head + std::string(size - head.size() - 2, 'x') + "\"}";
}

// A ping whose id nests `arrays` arrays: `arrays + 1` levels with the request object.
std::string nested_id(std::size_t arrays) {
    return R"({"cmd":"ping","id":)" + std::string(arrays, '[') + std::string(arrays, ']') + "}";
}

}  // namespace

TEST_CASE("limits: 8192 bytes pass, 8193 are too_large", "[command][limits]") {
    CHECK_FALSE(command::check_request_limits(padded(8192)));
    const auto refused = command::check_request_limits(padded(8193));
    REQUIRE(refused);
    CHECK(refused->code == "too_large");
    CHECK(refused->message == "the request is 8193 bytes, the limit is 8192");
}

TEST_CASE("limits: nesting is counted outside strings only", "[command][limits]") {
    CHECK_FALSE(command::nested_deeper_than(nested_id(31), 32));  // 32 levels
    CHECK(command::nested_deeper_than(nested_id(32), 32));        // 33
    CHECK_FALSE(command::nested_deeper_than("", 0));
    CHECK(command::nested_deeper_than("{", 0));
    CHECK_FALSE(command::nested_deeper_than(R"({"a":{"b":[1,{"c":[]}]}})", 5));
    CHECK(command::nested_deeper_than(R"({"a":{"b":[1,{"c":[]}]}})", 4));
    // Brackets in strings, escaped quotes and backslashes included, are text.
    CHECK_FALSE(command::nested_deeper_than(R"({"id":"[[[[{{{{"})", 1));
    CHECK_FALSE(command::nested_deeper_than(R"({"id":"\"[[[[\\"})", 1));
    CHECK(command::nested_deeper_than(R"({"id":"\\",  "x":[[]]})", 2));
    // Siblings do not add up: depth, not count.
    CHECK_FALSE(command::nested_deeper_than(R"([[],[],[],[],[]])", 2));
    // Stray closers do not buy depth.
    CHECK(command::nested_deeper_than("]]]]][[[", 2));
    const auto refused = command::check_request_limits(nested_id(32));
    REQUIRE(refused);
    CHECK(refused->code == "bad_json");
    CHECK(refused->message == "JSON nested deeper than 32 levels");
}

TEST_CASE("envelope: an oversize request is refused unread", "[command][envelope]") {
    // 70,000 nested arrays in `id`: 140 KB, the issue's crash. Never parsed.
    const auto huge = nested_id(70000);
    REQUIRE(huge.size() > 140000);
    const auto parses = command::request_parses();
    auto err = command::parse_request(huge);
    REQUIRE_FALSE(err);
    CHECK(err.error().code == "too_large");
    // The request path's reply to it echoes nothing of it: "id": null, "cmd": null.
    const auto reply = command::error_reply(nlohmann::json(nullptr), std::nullopt, err.error());
    CHECK(reply.dump() == R"({"cmd":null,"error":{"code":"too_large","message":"the request is )" +
                              std::to_string(huge.size()) +
                              R"( bytes, the limit is 8192"},"id":null,"ok":false})");

    err = command::parse_request(padded(8193));
    REQUIRE_FALSE(err);
    CHECK(err.error().code == "too_large");
    CHECK(command::request_parses() == parses);  // neither was parsed

    const auto at_limit = command::parse_request(padded(8192));
    REQUIRE(at_limit);  // parsed: its parameters are its planner's to read
    CHECK(at_limit->doc.contains("pad"));
    CHECK(*command::echo_of(nlohmann::json::parse(padded(8192))).id == 9);
}

TEST_CASE("envelope: nesting over 32 is bad_json, parsed never", "[command][envelope]") {
    const auto env = command::parse_request(nested_id(31));
    REQUIRE(env);
    CHECK(env->id->dump() == std::string(31, '[') + std::string(31, ']'));

    const auto parses = command::request_parses();
    auto err = command::parse_request(nested_id(32));
    REQUIRE_FALSE(err);
    CHECK(err.error().code == "bad_json");
    // 4,000 levels fit in 8192 bytes: refused by the scan just the same.
    err = command::parse_request(nested_id(4000));
    REQUIRE_FALSE(err);
    CHECK(err.error().code == "bad_json");
    CHECK(command::request_parses() == parses);
}
