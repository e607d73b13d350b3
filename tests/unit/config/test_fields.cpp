// The generic configuration reader and writer (lib/config/fields.hpp) on a section declared
// here: one fields() visit reads with every problem at its path and writes every key back,
// and what it writes reads again to the same struct.
#include <array>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config/fields.hpp"

namespace {

using gimbal::config::Fields;
using gimbal::config::Problem;
using gimbal::config::Problems;
using nlohmann::json;

enum class Colour { red, green };
constexpr std::array<gimbal::config::Named<Colour>, 2> colour_names{
    {{"red", Colour::red}, {"green", Colour::green}}};

struct Sample {
    std::string name;
    double rate_hz = 2;
    unsigned queue = 10;
    bool enabled = true;
    Colour colour = Colour::red;
    std::optional<std::string> file;
    std::optional<double> home;
    std::optional<std::uint8_t> id;
    std::vector<std::string> hosts;
    bool nested_flag = false;
    bool operator==(const Sample&) const = default;
};

template <class V>
void fields(V& v, Sample& s) {
    v.string("name", s.name, gimbal::config::Presence::required);
    v.number("rate_hz", s.rate_hz, {0.1, 50});
    v.integer("queue", s.queue, {1, 100});
    v.boolean("enabled", s.enabled);
    v.choice("colour", s.colour, colour_names);
    v.optional_string("file", s.file);
    v.optional_number("home", s.home, {-10, 10});
    v.optional_integer("id", s.id, {1, 255});
    v.string_list(
        "hosts", s.hosts, [](const std::string& h) { return h.find(':') == std::string::npos; },
        "must be an array of names", "must be a name without port");
    v.section("nested", [&](auto& n) { n.boolean("flag", s.nested_flag); });
    if (s.queue > 50 && !s.enabled) v.problem("queue", "more than 50 needs enabled");
}

struct Read {
    Sample sample;
    std::vector<std::string> problems;
};

Read read(const json& value) {
    std::vector<Problem> found;
    Problems problems(found);
    Fields f(value, "sample", problems);
    Read out;
    fields(f, out.sample);
    f.finish();
    for (const auto& p : found) out.problems.push_back(p.text());
    return out;
}

}  // namespace

TEST_CASE("a section reads its keys over the defaults and writes every key back") {
    const auto r = read(json{{"name", "a"},
                             {"rate_hz", 5},
                             {"colour", "green"},
                             {"id", 7},
                             {"hosts", {"x", "y"}},
                             {"nested", {{"flag", true}}}});
    REQUIRE(r.problems.empty());
    CHECK(r.sample.name == "a");
    CHECK(r.sample.rate_hz == 5);
    CHECK(r.sample.queue == 10);
    CHECK(r.sample.colour == Colour::green);
    CHECK(r.sample.id == 7);
    CHECK_FALSE(r.sample.file);
    CHECK(r.sample.hosts == std::vector<std::string>{"x", "y"});
    CHECK(r.sample.nested_flag);

    const json written = gimbal::config::write(r.sample);
    CHECK(written == json{{"name", "a"},
                          {"rate_hz", 5.0},
                          {"queue", 10},
                          {"enabled", true},
                          {"colour", "green"},
                          {"file", nullptr},
                          {"home", nullptr},
                          {"id", 7},
                          {"hosts", {"x", "y"}},
                          {"nested", {{"flag", true}}}});
    const auto again = read(written);
    CHECK(again.problems.empty());
    CHECK(again.sample == r.sample);
}

TEST_CASE("every problem is reported at its path, and a bad key keeps its default") {
    const auto r = read(json{{"rate_hz", 99},
                             {"queue", -1},
                             {"enabled", "yes"},
                             {"colour", "blue"},
                             {"file", ""},
                             {"home", "far"},
                             {"id", 256},
                             {"hosts", {"ok", "bad:1", 3}},
                             {"nested", 1},
                             {"rte_hz", 1}});
    CHECK(r.problems == std::vector<std::string>{
                            "sample.name: required",
                            "sample.rate_hz: must be between 0.1 and 50",
                            "sample.queue: must be between 1 and 100",
                            "sample.enabled: must be true or false",
                            "sample.colour: must be one of \"red\", \"green\"",
                            "sample.file: must be null or a non-empty string",
                            "sample.home: must be a number between -10 and 10",
                            "sample.id: must be between 1 and 255",
                            "sample.hosts[1]: must be a name without port",
                            "sample.hosts[2]: must be a name without port",
                            "sample.nested: must be an object",
                            "sample.rte_hz: unknown key (did you mean \"rate_hz\"?)",
                        });
    CHECK(r.sample.rate_hz == 2);
    CHECK(r.sample.queue == 10);
    CHECK(r.sample.colour == Colour::red);
    CHECK_FALSE(r.sample.id);
    CHECK(r.sample.hosts == std::vector<std::string>{"ok"});
}

TEST_CASE("a check across keys runs only while reading, and null is 'not set'") {
    auto r = read(json{{"name", "b"}, {"queue", 60}, {"enabled", false}, {"file", nullptr}});
    CHECK(r.problems == std::vector<std::string>{"sample.queue: more than 50 needs enabled"});
    CHECK_FALSE(r.sample.file);
    // The writer reports nothing, whatever the values.
    CHECK(gimbal::config::write(r.sample)["queue"] == 60);
    CHECK(read(json::array()).problems.front() == "sample: must be an object");
}

TEST_CASE("read_checked reads what the writer wrote, ignoring problems") {
    Sample s;
    s.name = "c";
    s.home = -2.5;
    s.colour = Colour::green;
    const json written = gimbal::config::write(s);
    CHECK(gimbal::config::read_checked<Sample>(written) == s);
    // A bad value keeps the default instead of failing: the caller checked it before.
    json bad = written;
    bad["rate_hz"] = "fast";
    CHECK(gimbal::config::read_checked<Sample>(bad).rate_hz == 2);
}
