// JSON Merge Patch (RFC 7396) and the STATE patches of delta streams (contract section 14).
#include <catch2/catch.hpp>
#include <cstdint>
#include <string>

#include "state/merge_patch.hpp"

using gimbal::state::merge_patch_apply;
using gimbal::state::merge_patch_diff;
using gimbal::state::same_ignoring_age;
using nlohmann::json;

namespace {

json applied(json target, const json& patch) {
    merge_patch_apply(target, patch);
    return target;
}

// `value` as a receiver that merges patches holds it: object members that are null are gone
// (arrays are kept verbatim).
json without_nulls(const json& value) {
    if (!value.is_object()) return value;
    json out = json::object();
    for (auto it = value.begin(); it != value.end(); ++it)
        if (!it->is_null()) out[it.key()] = without_nulls(*it);
    return out;
}

// "k3", "s1": names and strings of the generated documents. (Built with append: GCC 12 -O3
// warns falsely (-Wrestrict) about "literal" + std::string.)
std::string name(const char* prefix, int n) {
    std::string out(prefix);
    out.append(std::to_string(n));
    return out;
}

// A small deterministic generator of STATE-like documents (xorshift).
struct Random {
    std::uint64_t s;
    std::uint64_t next() {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        return s;
    }
    int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

json random_value(Random& r, int depth) {
    switch (r.below(depth > 2 ? 4 : 7)) {
        case 0:
            return nullptr;
        case 1:
            return r.below(5);
        case 2:
            return r.below(2) == 0;
        case 3:
            return name("s", r.below(4));
        case 4: {
            json a = json::array();
            for (int i = r.below(3); i > 0; --i) a.push_back(random_value(r, depth + 1));
            return a;
        }
        default: {
            json o = json::object();
            for (int i = r.below(5); i > 0; --i)
                o[name("k", r.below(6))] = random_value(r, depth + 1);
            if (r.below(2) == 0) o["age_s"] = r.below(100) / 10.0;
            return o;
        }
    }
}

// Changes a few members of `doc`, at any depth.
void mutate(Random& r, json& doc, int depth = 0) {
    if (!doc.is_object()) return;
    for (auto it = doc.begin(); it != doc.end(); ++it) {
        if (it.key() == "age_s") {
            *it = r.below(100) / 10.0;
        } else if (it->is_object() && r.below(2) == 0) {
            mutate(r, *it, depth + 1);
        } else if (r.below(4) == 0) {
            *it = random_value(r, depth + 1);
        }
    }
    if (r.below(4) == 0) doc[name("k", r.below(8))] = random_value(r, depth + 1);
    if (r.below(5) == 0 && !doc.empty()) doc.erase(doc.begin());
}

}  // namespace

TEST_CASE("merge_patch_apply: every example of RFC 7396 appendix A") {
    struct Case {
        const char* target;
        const char* patch;
        const char* result;
    };
    const Case cases[] = {
        {R"({"a":"b"})", R"({"a":"c"})", R"({"a":"c"})"},
        {R"({"a":"b"})", R"({"b":"c"})", R"({"a":"b","b":"c"})"},
        {R"({"a":"b"})", R"({"a":null})", R"({})"},
        {R"({"a":"b","b":"c"})", R"({"a":null})", R"({"b":"c"})"},
        {R"({"a":["b"]})", R"({"a":"c"})", R"({"a":"c"})"},
        {R"({"a":"c"})", R"({"a":["b"]})", R"({"a":["b"]})"},
        {R"({"a":{"b":"c"}})", R"({"a":{"b":"d","c":null}})", R"({"a":{"b":"d"}})"},
        {R"({"a":[{"b":"c"}]})", R"({"a":[1]})", R"({"a":[1]})"},
        {R"(["a","b"])", R"(["c","d"])", R"(["c","d"])"},
        {R"({"a":"b"})", R"(["c"])", R"(["c"])"},
        {R"({"a":"foo"})", R"(null)", R"(null)"},
        {R"({"a":"foo"})", R"("bar")", R"("bar")"},
        {R"({"e":null})", R"({"a":1})", R"({"e":null,"a":1})"},
        {R"([1,2])", R"({"a":"b","c":null})", R"({"a":"b"})"},
        {R"({})", R"({"a":{"bb":{"ccc":null}}})", R"({"a":{"bb":{}}})"},
    };
    for (const auto& c : cases) {
        INFO(c.target << " + " << c.patch);
        CHECK(applied(json::parse(c.target), json::parse(c.patch)) == json::parse(c.result));
    }
}

TEST_CASE("merge_patch_apply: the example of RFC 7396 section 3") {
    const json target = json::parse(R"({"title": "Goodbye!",
        "author": {"givenName": "John", "familyName": "Doe"},
        "tags": ["example", "sample"], "content": "This will be unchanged"})");
    const json patch = json::parse(R"({"title": "Hello!", "phoneNumber": "+01-123-456-7890",
        "author": {"familyName": null}, "tags": ["example"]})");
    CHECK(applied(target, patch) == json::parse(R"({"title": "Hello!",
        "author": {"givenName": "John"}, "tags": ["example"],
        "content": "This will be unchanged", "phoneNumber": "+01-123-456-7890"})"));
}

TEST_CASE("merge_patch_diff sends only what changed, at any depth") {
    const json from = {{"protocol", "orion"},
                       {"stale", false},
                       {"telemetry", {{"pan", 1.0}, {"tilt", -2.0}, {"target", {{"lat", 45.0}}}}},
                       {"gps", nullptr}};
    json to = from;
    to["telemetry"]["pan"] = 1.5;
    to["telemetry"]["target"]["lat"] = 45.1;
    CHECK(merge_patch_diff(from, to) ==
          json{{"telemetry", {{"pan", 1.5}, {"target", {{"lat", 45.1}}}}}});
    CHECK(merge_patch_diff(from, from) == json::object());
}

TEST_CASE("merge_patch_diff: arrays whole, null as null, a new member whole") {
    const json from = {{"lasers", {{{"index", 0}, {"firing", false}}, {{"index", 1}}}},
                       {"target", {{"lat", 1}}},
                       {"gone", 3},
                       {"gps", nullptr}};
    json to = from;
    to["lasers"][0]["firing"] = true;
    to["target"] = nullptr;
    to.erase("gone");
    to["gps"] = {{"sats", 7}, {"fix", nullptr}};
    CHECK(merge_patch_diff(from, to) ==
          json{{"lasers", {{{"index", 0}, {"firing", true}}, {{"index", 1}}}},
               {"target", nullptr},
               {"gone", nullptr},
               {"gps", {{"sats", 7}, {"fix", nullptr}}}});
    // A member missing on one side and null on the other is no change.
    CHECK(merge_patch_diff(json{{"a", nullptr}}, json::object()) == json::object());
    CHECK(merge_patch_diff(json::object(), json{{"a", nullptr}}) == json::object());
}

TEST_CASE("merge_patch_diff: age_s alone is no change; it rides along with other changes") {
    const json from = {{"ins", {{"mode", "nav"}, {"age_s", 0.4}}},
                       {"gps", {{"sats", 9}, {"age_s", 0.4}}},
                       {"lasers", {{{"firing", false}, {"age_s", 0.2}}}}};
    json to = from;
    to["ins"]["age_s"] = 0.5;
    to["gps"]["age_s"] = 0.5;
    to["lasers"][0]["age_s"] = 0.3;
    CHECK(merge_patch_diff(from, to) == json::object());
    to["gps"]["sats"] = 10;
    CHECK(merge_patch_diff(from, to) == json{{"gps", {{"sats", 10}, {"age_s", 0.5}}}});
    // An array that changed goes whole, with the ages it holds.
    to["lasers"][0]["firing"] = true;
    CHECK(merge_patch_diff(from, to)["lasers"] ==
          json::array({{{"firing", true}, {"age_s", 0.3}}}));
    // Nested: the inner object's age goes with its change, the outer one's too.
    const json a = {{"software", {{"age_s", 1.0}, {"clevis", {{"v", 1}, {"age_s", 1.0}}}}}};
    json b = a;
    b["software"]["age_s"] = 2.0;
    b["software"]["clevis"]["age_s"] = 2.0;
    CHECK(merge_patch_diff(a, b) == json::object());
    b["software"]["clevis"]["v"] = 2;
    CHECK(merge_patch_diff(a, b) ==
          json{{"software", {{"age_s", 2.0}, {"clevis", {{"v", 2}, {"age_s", 2.0}}}}}});
}

TEST_CASE("merge_patch_diff then apply gives the new document (nulls as missing, ages aside)") {
    Random r{0x9e3779b97f4a7c15ULL};
    for (int round = 0; round < 300; ++round) {
        json doc = json::object();
        for (int i = 0; i < 6; ++i) doc[name("k", i)] = random_value(r, 1);
        json held = doc;  // what a receiver holds after the full push
        for (int push = 0; push < 20; ++push) {
            json next = doc;
            mutate(r, next);
            const json patch = merge_patch_diff(doc, next);
            merge_patch_apply(held, patch);
            INFO("round " << round << " push " << push << "\nfrom " << doc << "\nto   " << next
                          << "\npatch " << patch << "\nheld " << held);
            REQUIRE(same_ignoring_age(without_nulls(held), without_nulls(next)));
            REQUIRE(same_ignoring_age(without_nulls(held), next));
            doc = std::move(next);
        }
    }
}

TEST_CASE("same_ignoring_age compares values without age_s, missing as null") {
    CHECK(same_ignoring_age(json{{"a", 1}, {"age_s", 1}}, json{{"a", 1}, {"age_s", 2}}));
    CHECK(same_ignoring_age(json{{"a", 1}}, json{{"a", 1}, {"age_s", 2}}));
    CHECK(same_ignoring_age(json{{"a", nullptr}}, json::object()));
    CHECK_FALSE(same_ignoring_age(json{{"a", 1}}, json{{"a", 2}}));
    CHECK_FALSE(same_ignoring_age(json{{"a", 1}}, json::object()));
    CHECK_FALSE(same_ignoring_age(json::array({1, 2}), json::array({1})));
    CHECK(same_ignoring_age(json::array({{{"x", 1}, {"age_s", 1}}}), json::array({{{"x", 1}}})));
}
