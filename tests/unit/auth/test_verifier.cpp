#include <catch2/catch.hpp>

#include "auth/hmac.hpp"
#include "auth/roles.hpp"
#include "auth/signed_envelope.hpp"
#include "auth/verifier.hpp"

using namespace gimbal::auth;
using nlohmann::json;

namespace {

constexpr std::int64_t now_ms = 1'790'000'000'000;

Key make_key(std::string id, std::uint8_t fill) {
    Key k{std::move(id), std::vector<std::uint8_t>(32, fill), {}};
    k.roles.add(Role::observe);
    k.roles.add(Role::control);
    return k;
}

SignedEnvelope envelope_of(const std::string& datagram) {
    auto read = parse_signed(json::parse(datagram));
    REQUIRE(read);
    REQUIRE(read->has_value());
    return **read;
}

std::string signed_request(const Key& key, json request) {
    return sign(key.id, key.secret, request.dump());
}

std::string reason(const gimbal::Result<Verified>& r) {
    REQUIRE_FALSE(r);
    return r.error().message;
}

}  // namespace

TEST_CASE("a well-signed fresh request verifies once") {
    const Key ops = make_key("ops", 1);
    Verifier v({ops}, 30);
    const auto datagram =
        signed_request(ops, {{"cmd", "state"}, {"ts", now_ms}, {"nonce", "abcdefgh"}});
    auto r = v.verify(envelope_of(datagram), now_ms + 1000);
    REQUIRE(r);
    CHECK(r->key->id == "ops");
    CHECK(r->request["cmd"] == "state");
    // The same datagram again is a replay.
    CHECK_THAT(reason(v.verify(envelope_of(datagram), now_ms + 2000)), Catch::Contains("replayed"));
}

TEST_CASE("every rejection names its reason") {
    const Key ops = make_key("ops", 1);
    const Key other = make_key("ops", 2);  // same id, another secret
    Verifier v({ops}, 30);
    const json good = {{"cmd", "state"}, {"ts", now_ms}, {"nonce", "nonce-0001"}};

    CHECK_THAT(reason(v.verify(envelope_of(signed_request(make_key("eve", 1), good)), now_ms)),
               Catch::Contains("unknown key 'eve'"));
    CHECK_THAT(reason(v.verify(envelope_of(signed_request(other, good)), now_ms)),
               Catch::Contains("bad MAC"));

    auto tampered = envelope_of(signed_request(ops, good));
    tampered.payload[2] ^= 1;
    CHECK_THAT(reason(v.verify(tampered, now_ms)), Catch::Contains("bad MAC"));
    auto bad_hex = envelope_of(signed_request(ops, good));
    bad_hex.mac = "xyz";
    CHECK_THAT(reason(v.verify(bad_hex, now_ms)), Catch::Contains("bad MAC"));

    CHECK_THAT(reason(v.verify(envelope_of(signed_request(ops, good)), now_ms + 30'001)),
               Catch::Contains("behind"));
    CHECK_THAT(reason(v.verify(envelope_of(signed_request(ops, good)), now_ms - 30'001)),
               Catch::Contains("ahead of"));

    json no_ts = good;
    no_ts.erase("ts");
    CHECK_THAT(reason(v.verify(envelope_of(signed_request(ops, no_ts)), now_ms)),
               Catch::Contains("\"ts\""));
    json float_ts = good;
    float_ts["ts"] = 1.5;
    CHECK_THAT(reason(v.verify(envelope_of(signed_request(ops, float_ts)), now_ms)),
               Catch::Contains("\"ts\""));
    for (const std::string& nonce : {std::string("short"), std::string(65, 'n')}) {
        json n = good;
        n["nonce"] = nonce;
        CHECK_THAT(reason(v.verify(envelope_of(signed_request(ops, n)), now_ms)),
                   Catch::Contains("nonce"));
    }
    const auto not_object = sign(ops.id, ops.secret, "[1,2]");
    auto r = v.verify(envelope_of(not_object), now_ms);
    REQUIRE_FALSE(r);
    CHECK(r.error().code == gimbal::ErrorCode::bad_json);
}

TEST_CASE("a nonce may be used again once its ts has left the window") {
    const Key ops = make_key("ops", 1);
    Verifier v({ops}, 30);
    const json first = {{"cmd", "state"}, {"ts", now_ms}, {"nonce", "same-nonce"}};
    CHECK(static_cast<bool>(v.verify(envelope_of(signed_request(ops, first)), now_ms)));
    // 31 s later the old request fails the ts check; a new ts with the same nonce passes.
    json later = first;
    later["ts"] = now_ms + 31'000;
    CHECK(static_cast<bool>(v.verify(envelope_of(signed_request(ops, later)), now_ms + 31'000)));
}

TEST_CASE("nonces are per key") {
    const Key a = make_key("a", 1);
    const Key b = make_key("b", 2);
    Verifier v({a, b}, 30);
    const json req = {{"cmd", "state"}, {"ts", now_ms}, {"nonce", "shared-nonce"}};
    CHECK(static_cast<bool>(v.verify(envelope_of(signed_request(a, req)), now_ms)));
    CHECK(static_cast<bool>(v.verify(envelope_of(signed_request(b, req)), now_ms)));
}

TEST_CASE("a full nonce window refuses instead of forgetting") {
    const Key ops = make_key("ops", 1);
    Verifier v({ops}, 30, 2);
    for (const char* n : {"nonce-001", "nonce-002"}) {
        const json req = {{"cmd", "state"}, {"ts", now_ms}, {"nonce", n}};
        CHECK(static_cast<bool>(v.verify(envelope_of(signed_request(ops, req)), now_ms)));
    }
    const json third = {{"cmd", "state"}, {"ts", now_ms}, {"nonce", "nonce-003"}};
    CHECK_THAT(reason(v.verify(envelope_of(signed_request(ops, third)), now_ms)),
               Catch::Contains("too many"));
    // Once the first two expire there is room again.
    json fourth = third;
    fourth["ts"] = now_ms + 40'000;
    CHECK(static_cast<bool>(v.verify(envelope_of(signed_request(ops, fourth)), now_ms + 40'000)));
}

TEST_CASE("malformed signed envelopes are told apart from plain requests") {
    const auto plain = [](const json& j) {
        auto r = parse_signed(j);
        REQUIRE(r);
        return !r->has_value();
    };
    CHECK(plain(json{{"cmd", "ping"}}));
    CHECK(plain(json::array()));
    auto bad = [](const json& j) {
        auto r = parse_signed(j);
        if (r) return false;
        CHECK(r.error().code == gimbal::command::code::bad_request);
        return true;
    };
    CHECK(bad(json{{"signed", 1}}));
    CHECK(bad(json{{"signed", {{"key", "a"}, {"payload", "{}"}}}}));
    CHECK(bad(json{{"signed", {{"key", "a"}, {"payload", "{}"}, {"mac", 5}}}}));
    CHECK(bad(json{{"signed", {{"key", "a"}, {"payload", "{}"}, {"mac", "00"}, {"x", "y"}}}}));
    CHECK(bad(json{{"signed", {{"key", "a"}, {"payload", "{}"}, {"mac", "00"}}}, {"cmd", "x"}}));
}

TEST_CASE("roles: observe, control, laser only when firing") {
    CHECK_FALSE(required_role("ping", json::object()));
    CHECK_FALSE(required_role("list", json::object()));
    CHECK(required_role("state", json::object()) == Role::observe);
    CHECK(required_role("subscribe", json::object()) == Role::observe);
    CHECK(required_role("geopoint", json::object()) == Role::control);
    CHECK(required_role("vehicle", json::object()) == Role::control);
    CHECK(required_role("laser", json{{"fire", false}}) == Role::control);
    CHECK(required_role("laser", json{{"fire", true}}) == Role::laser);
    CHECK(required_role("laser", json::object()) == Role::laser);
    CHECK(required_role("laser", json{{"fire", 0}}) == Role::laser);
    CHECK(parse_role("laser") == Role::laser);
    CHECK_FALSE(parse_role("admin"));
}

TEST_CASE("authenticate checks key and MAC only; accept spends the nonce") {
    const Key ops = make_key("ops", 1);
    Verifier v({ops}, 30);
    const auto good = envelope_of(
        signed_request(ops, {{"cmd", "state"}, {"ts", now_ms}, {"nonce", "nonce-0001"}}));
    // Authenticating again and again changes nothing: the nonce is still fresh after.
    for (int i = 0; i < 3; ++i) {
        auto key = v.authenticate(good);
        REQUIRE(key);
        CHECK((*key)->id == "ops");
    }
    auto forged = good;
    forged.mac[0] = forged.mac[0] == '0' ? '1' : '0';
    auto refused = v.authenticate(forged);
    REQUIRE_FALSE(refused);
    CHECK_THAT(refused.error().message, Catch::Contains("bad MAC"));

    CHECK(static_cast<bool>(v.accept(ops, json::parse(good.payload), now_ms)));
    CHECK_THAT(reason(v.accept(ops, json::parse(good.payload), now_ms)),
               Catch::Contains("replayed"));
}

TEST_CASE("a signed payload meets the request limits before it is parsed") {
    const Key ops = make_key("ops", 1);
    Verifier v({ops}, 30);
    const std::string deep = R"({"cmd":"state","ts":)" + std::to_string(now_ms) +
                             R"(,"nonce":"nonce-0002","id":)" + std::string(40, '[') +
                             std::string(40, ']') + "}";
    auto r = v.verify(envelope_of(sign(ops.id, ops.secret, deep)), now_ms);
    REQUIRE_FALSE(r);
    CHECK(r.error().code == gimbal::ErrorCode::bad_json);
    CHECK_THAT(r.error().message, Catch::Contains("nested deeper than 32"));

    const std::string big = R"({"cmd":"state","ts":)" + std::to_string(now_ms) +
                            R"(,"nonce":"nonce-0003","pad":")" + std::string(9000, 'x') + "\"}";
    r = v.verify(envelope_of(sign(ops.id, ops.secret, big)), now_ms);
    REQUIRE_FALSE(r);
    CHECK(r.error().code == gimbal::ErrorCode::too_large);
}
