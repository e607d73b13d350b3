// The one result type: the contract's closed list of error codes with their wire spelling,
// Result<T>, and the APIs that answer with it (signed envelopes, STATE key lists).
#include <catch2/catch.hpp>
#include <sstream>

#include "auth/signed_envelope.hpp"
#include "command/result.hpp"
#include "state/messages.hpp"

using namespace gimbal;
using command::ErrorCode;
using nlohmann::json;

TEST_CASE("error codes: contract section 4's list, in its order, spelt for the wire") {
    const std::vector<std::string> contract = {
        "bad_json",       "too_large",    "unknown_cmd", "bad_request", "out_of_range",
        "unknown_gimbal", "unsupported",  "unavailable", "link_down",   "forbidden",
        "busy",           "rate_limited", "internal"};
    REQUIRE(command::error_code_names.size() == contract.size());
    for (std::size_t i = 0; i < contract.size(); ++i) {
        const auto c = static_cast<ErrorCode>(i);
        CHECK(command::to_string(c) == contract[i]);
        CHECK(command::parse_error_code(contract[i]) == c);
        CHECK(c == contract[i]);
        CHECK(json(c) == contract[i]);
        std::ostringstream out;
        out << c;
        CHECK(out.str() == contract[i]);
    }
    CHECK_FALSE(command::parse_error_code("teapot"));
    CHECK(command::code::link_down == ErrorCode::link_down);
    // An Error in a reply object carries the spelling.
    const command::Error e{command::code::busy, "full"};
    CHECK(json{{"code", e.code}, {"message", e.message}} ==
          json{{"code", "busy"}, {"message", "full"}});
}

TEST_CASE("Result: a value or an error") {
    command::Result<int> ok = 7;
    REQUIRE(ok);
    CHECK(ok.value() == 7);
    CHECK(*ok == 7);
    command::Result<int> bad{command::code::unavailable, "not yet"};
    REQUIRE_FALSE(bad);
    CHECK(bad.error().code == ErrorCode::unavailable);
    CHECK(bad.error().message == "not yet");
    command::Status fine;
    CHECK(fine.ok());
    command::Status refused = command::Error{command::code::forbidden, "no"};
    CHECK_FALSE(refused.ok());
    CHECK(refused.error().code == ErrorCode::forbidden);
    command::Result<std::string> text = std::string("moved");
    CHECK(std::move(text).value() == "moved");
}

TEST_CASE("read_state_keys: the names, or bad_request naming the problem") {
    auto keys = state::read_state_keys(json{"telemetry", "lasers", "telemetry"});
    REQUIRE(keys);
    CHECK(*keys == std::vector<std::string>{"telemetry", "lasers"});
    auto unknown = state::read_state_keys(json{"telemtry"});
    REQUIRE_FALSE(unknown);
    CHECK(unknown.error().code == ErrorCode::bad_request);
    CHECK(unknown.error().message.find("'telemtry'") != std::string::npos);
    CHECK_FALSE(state::read_state_keys(json("telemetry")));
}

TEST_CASE("parse_signed: not signed, signed, or bad_request") {
    auto plain = auth::parse_signed(json{{"cmd", "ping"}});
    REQUIRE(plain);
    CHECK_FALSE(plain->has_value());
    auto envelope =
        auth::parse_signed(json{{"signed", {{"key", "k"}, {"payload", "{}"}, {"mac", "00"}}}});
    REQUIRE(envelope);
    REQUIRE(envelope->has_value());
    CHECK((*envelope)->key == "k");
    auto malformed = auth::parse_signed(json{{"signed", {{"key", "k"}}}});
    REQUIRE_FALSE(malformed);
    CHECK(malformed.error().code == ErrorCode::bad_request);
    CHECK(malformed.error().message.find("\"mac\"") != std::string::npos);
}
