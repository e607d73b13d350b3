// Structured logs: exact JSON and text lines, level filtering, the log file and its reopen
// after logrotate, and the roll-up of repeated events with an injected clock.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "journal.hpp"
#include "log_rollup.hpp"
#include "logging.hpp"

// A named namespace: an alias `log` at global scope would clash with ::log() of <cmath>.
namespace logging_test {

namespace log = gimbal::log;
using nlohmann::json;
using namespace std::chrono;
using namespace std::chrono_literals;

namespace {

// 2026-11-21T06:41:50.123456Z
log::SystemTime example_time() {
    return sys_days{year{2026} / November / 21} + 6h + 41min + 50s + 123456us;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        std::string pattern =
            (std::filesystem::temp_directory_path() / "gimbald-log-XXXXXX").string();
        REQUIRE(mkdtemp(pattern.data()) != nullptr);
        path = pattern;
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
};

// A steady clock the test moves by hand.
struct FakeSteadyClock {
    steady_clock::time_point now{};
    log::RateLimitedLog::Clock function() {
        return [this] { return now; };
    }
};

}  // namespace

TEST_CASE("timestamps are ISO-8601 UTC with microseconds", "[logging]") {
    CHECK(log::iso8601_utc(example_time()) == "2026-11-21T06:41:50.123456Z");
    CHECK(log::iso8601_utc(log::SystemTime{}) == "1970-01-01T00:00:00.000000Z");
    CHECK(log::iso8601_utc(sys_days{year{2024} / February / 29} + 23h + 59min + 59s + 999999us) ==
          "2024-02-29T23:59:59.999999Z");
}

TEST_CASE("a JSON record is one object per line, keys in a fixed order", "[logging]") {
    const json fields = {{"gimbal", "main"}, {"endpoint", "192.168.1.20:8747"}, {"attempt", 3}};
    const log::Record record{example_time(), log::Level::info, "link_up", "link connected",
                             &fields};
    CHECK(log::format_json(record) ==
          R"({"ts":"2026-11-21T06:41:50.123456Z","level":"info","event":"link_up",)"
          R"("msg":"link connected","attempt":3,"endpoint":"192.168.1.20:8747","gimbal":"main"})");

    SECTION("no fields") {
        const log::Record bare{example_time(), log::Level::warn, "stop", "bye", nullptr};
        CHECK(log::format_json(bare) ==
              R"({"ts":"2026-11-21T06:41:50.123456Z","level":"warn","event":"stop","msg":"bye"})");
    }
    SECTION("awkward text stays on one line and valid") {
        const json odd = {{"text", "line1\nline2 \"quoted\""}, {"raw", std::string("\xff\xfe", 2)}};
        const log::Record r{example_time(), log::Level::error, "gimbal_debug", "a\nb", &odd};
        const std::string line = log::format_json(r);
        CHECK(line.find('\n') == std::string::npos);
        const json parsed = json::parse(line);
        CHECK(parsed["msg"] == "a\nb");
        CHECK(parsed["text"] == "line1\nline2 \"quoted\"");
        CHECK(parsed["raw"] == "\xEF\xBF\xBD\xEF\xBF\xBD");  // U+FFFD twice
    }
    SECTION("fields cannot shadow the record's keys") {
        const json clash = {{"msg", "other"}, {"level", 1}, {"gimbal", "a"}};
        const log::Record r{example_time(), log::Level::info, "command", "ok", &clash};
        const json parsed = json::parse(log::format_json(r));
        CHECK(parsed["msg"] == "ok");
        CHECK(parsed["level"] == "info");
        CHECK(parsed["field_msg"] == "other");
        CHECK(parsed["field_level"] == 1);
        CHECK(parsed["gimbal"] == "a");
    }
    SECTION("non-object fields are kept under `fields`") {
        const json list = json::array({1, 2});
        const log::Record r{example_time(), log::Level::debug, "x", "y", &list};
        CHECK(json::parse(log::format_json(r))["fields"] == list);
    }
}

TEST_CASE("a text record reads well at a terminal", "[logging]") {
    const json fields = {{"gimbal", "main"}, {"endpoint", "192.168.1.20:8747"}};
    const log::Record record{example_time(), log::Level::info, "link_up", "link connected",
                             &fields};
    CHECK(log::format_text(record) ==
          "2026-11-21 06:41:50.123 INFO  link_up endpoint=192.168.1.20:8747 gimbal=main: "
          "link connected");

    const json mixed = {{"text", "two words"}, {"ok", false}, {"n", 1.5},
                        {"none", nullptr},     {"empty", ""}, {"vec", {1, 2}}};
    const log::Record r{example_time(), log::Level::error, "command", "", &mixed};
    CHECK(log::format_text(r) ==
          "2026-11-21 06:41:50.123 ERROR command empty=\"\" n=1.5 none=null ok=false "
          "text=\"two words\" vec=[1,2]");

    const log::Record warn{example_time(), log::Level::warn, "stop", "bye", nullptr};
    CHECK(log::format_text(warn) == "2026-11-21 06:41:50.123 WARN  stop: bye");
}

TEST_CASE("text records escape control characters: no request starts a line", "[logging]") {
    // The issue's forgery: an unknown command whose name carries a newline and a fake line.
    const std::string forged = "nosuch\n2026-11-21 06:41:50.123 WARN  audit fire=true: ok";
    const json fields = {{"cmd", forged}, {"src", "127.0.0.1:5000"}};
    const std::string msg = "unknown command '" + forged + "'";
    const log::Record record{example_time(), log::Level::info, "command", msg, &fields};
    const std::string line = log::format_text(record);
    CHECK(line.find('\n') == std::string::npos);
    CHECK(line ==
          "2026-11-21 06:41:50.123 INFO  command "
          "cmd=\"nosuch\\n2026-11-21 06:41:50.123 WARN  audit fire=true: ok\" src=127.0.0.1:5000: "
          "unknown command 'nosuch\\n2026-11-21 06:41:50.123 WARN  audit fire=true: ok'");

    // Every control character, DEL and C1 (U+0085 NEXT LINE) in message, keys and values.
    const std::string nasty = std::string("a\rb\tc") + '\0' + "d\x1b[31me\x7f" + "f\xc2\x85g\\h";
    const json odd = {{"k\ney", nasty}};
    const log::Record r{example_time(), log::Level::warn, "ev\nent", nasty, &odd};
    const std::string text = log::format_text(r);
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        CHECK((byte >= 0x20 && byte != 0x7f));
    }
    CHECK(text.find("\xc2\x85") == std::string::npos);
    CHECK(text ==
          "2026-11-21 06:41:50.123 WARN  ev\\nent "
          "k\\ney=\"a\\rb\\tc\\u0000d\\u001b[31me\\x7ff\\u0085g\\\\h\": "
          "a\\rb\\tc\\x00d\\x1b[31me\\x7ff\\u0085g\\\\h");
    // Plain words stay as they were.
    const json plain = {{"gimbal", "main"}};
    const log::Record p{example_time(), log::Level::info, "link_up", "link connected", &plain};
    CHECK(log::format_text(p) ==
          "2026-11-21 06:41:50.123 INFO  link_up gimbal=main: link connected");
}

TEST_CASE("journal: priorities, field names and fields of a record", "[logging][journal]") {
    CHECK(log::journal_priority(log::Level::error) == 3);
    CHECK(log::journal_priority(log::Level::warn) == 4);
    CHECK(log::journal_priority(log::Level::info) == 6);
    CHECK(log::journal_priority(log::Level::debug) == 7);
    CHECK(log::journal_priority(log::Level::trace) == 7);

    CHECK(log::journal_field_name("event") == "EVENT");
    CHECK(log::journal_field_name("max_per_client") == "MAX_PER_CLIENT");
    CHECK(log::journal_field_name("a.b-c") == "A_B_C");
    CHECK(log::journal_field_name("message") == "GIMBALD_MESSAGE");  // the journal's own
    CHECK(log::journal_field_name("priority") == "GIMBALD_PRIORITY");
    CHECK(log::journal_field_name("_pid") == "GIMBALD__PID");  // trusted fields start with _
    CHECK(log::journal_field_name("1st") == "GIMBALD_1ST");
    CHECK(log::journal_field_name("") == "GIMBALD_");
    CHECK(log::journal_field_name(std::string(64, 'k')) == std::string(64, 'K'));
    CHECK(log::journal_field_name(std::string(65, 'k')).empty());  // over journald's limit

    const json fields = {{"gimbal", "main"},
                         {"src", "10.0.0.7:4000"},
                         {"ok", true},
                         {"index", 0},
                         {"id", nullptr},
                         {"keys", {1, 2}},
                         {"error", {{"code", "x"}}},
                         {"msg", "shadowed"},
                         {"text", "two\nlines"}};
    const log::Record record{example_time(), log::Level::warn, "laser_fire", "laser fire commanded",
                             &fields};
    const std::string line = log::format_json(record);
    const auto got = log::journal_fields(record, line);
    const std::vector<std::string> want = {"MESSAGE=" + line,
                                           "PRIORITY=4",
                                           "SYSLOG_IDENTIFIER=gimbald",
                                           "TS=2026-11-21T06:41:50.123456Z",
                                           "LEVEL=warn",
                                           "EVENT=laser_fire",
                                           "MSG=laser fire commanded",
                                           "GIMBAL=main",
                                           "INDEX=0",
                                           "FIELD_MSG=shadowed",
                                           "OK=true",
                                           "SRC=10.0.0.7:4000",
                                           "TEXT=two\nlines"};
    CHECK(got == want);
}

TEST_CASE("journal: JOURNAL_STREAM names a device and an inode", "[logging][journal]") {
    CHECK(log::journal_stream_matches("8:12345", 8, 12345));
    CHECK_FALSE(log::journal_stream_matches("8:12345", 8, 12346));
    CHECK_FALSE(log::journal_stream_matches("9:12345", 8, 12345));
    CHECK_FALSE(log::journal_stream_matches("8:", 8, 0));
    CHECK_FALSE(log::journal_stream_matches(":1", 0, 1));
    CHECK_FALSE(log::journal_stream_matches("8-12345", 8, 12345));
    CHECK_FALSE(log::journal_stream_matches("8:12345x", 8, 12345));
    CHECK_FALSE(log::journal_stream_matches("", 0, 0));
    // Not set, or naming another file than standard output: not the journal.
    const char* saved = std::getenv("JOURNAL_STREAM");
    const std::string keep = saved != nullptr ? saved : "";
    ::unsetenv("JOURNAL_STREAM");
    CHECK_FALSE(log::stdout_is_journal());
    ::setenv("JOURNAL_STREAM", "1:1", 1);
    CHECK_FALSE(log::stdout_is_journal());
    if (saved != nullptr)
        ::setenv("JOURNAL_STREAM", keep.c_str(), 1);
    else
        ::unsetenv("JOURNAL_STREAM");
}

TEST_CASE("level and format names", "[logging]") {
    for (auto level : {log::Level::trace, log::Level::debug, log::Level::info, log::Level::warn,
                       log::Level::error}) {
        CHECK(log::parse_level(log::to_string(level)) == level);
    }
    CHECK_FALSE(log::parse_level("warning"));
    CHECK_FALSE(log::parse_level("INFO"));
    CHECK(log::parse_format("json") == log::Format::json);
    CHECK(log::parse_format("text") == log::Format::text);
    CHECK_FALSE(log::parse_format("xml"));
}

TEST_CASE("the logger writes formatted lines and filters by level", "[logging]") {
    std::ostringstream out;
    log::Logger logger({}, out, [] { return example_time(); });

    logger.write(log::Level::info, "start", "gimbald started", {{"version", "1.2.3"}});
    logger.write(log::Level::debug, "detail", "hidden at info");
    logger.write(log::Level::error, "link_error", "refused", {{"gimbal", "main"}});
    auto lines = lines_of(out.str());
    REQUIRE(lines.size() == 2);
    CHECK(lines[0] == R"({"ts":"2026-11-21T06:41:50.123456Z","level":"info","event":"start",)"
                      R"("msg":"gimbald started","version":"1.2.3"})");
    CHECK(json::parse(lines[1])["event"] == "link_error");
    CHECK_FALSE(logger.enabled(log::Level::debug));
    CHECK(logger.enabled(log::Level::warn));

    logger.set_level(log::Level::trace);
    logger.write(log::Level::trace, "bytes", "rx");
    CHECK(lines_of(out.str()).size() == 3);

    logger.configure({log::Level::warn, log::Format::text, std::nullopt});
    CHECK(logger.level() == log::Level::warn);
    CHECK(logger.format() == log::Format::text);
    logger.write(log::Level::info, "ignored", "below warn");
    logger.write(log::Level::warn, "laser_deadman", "fire 0 sent", {{"index", 0}});
    lines = lines_of(out.str());
    REQUIRE(lines.size() == 4);
    CHECK(lines[3] == "2026-11-21 06:41:50.123 WARN  laser_deadman index=0: fire 0 sent");
}

TEST_CASE("the log file is appended to and reopened after logrotate", "[logging]") {
    TempDir dir;
    const auto file = dir.path / "gimbald.log";
    const auto rotated = dir.path / "gimbald.log.1";
    std::ostringstream console;
    log::Logger logger({log::Level::info, log::Format::json, file.string()}, console);

    logger.write(log::Level::info, "first", "a");
    std::filesystem::rename(file, rotated);         // what logrotate does
    logger.write(log::Level::info, "second", "b");  // still the old, renamed file
    CHECK(logger.reopen());
    logger.write(log::Level::info, "third", "c");

    const auto old_lines = lines_of(read_file(rotated));
    REQUIRE(old_lines.size() == 2);
    CHECK(json::parse(old_lines[0])["event"] == "first");
    CHECK(json::parse(old_lines[1])["event"] == "second");
    const auto new_lines = lines_of(read_file(file));
    REQUIRE(new_lines.size() == 1);
    CHECK(json::parse(new_lines[0])["event"] == "third");
    // Standard output got everything.
    CHECK(lines_of(console.str()).size() == 3);

    SECTION("a failed reopen is reported, keeps the console, and is retried") {
        std::filesystem::remove_all(dir.path);
        CHECK_FALSE(logger.reopen());
        logger.write(log::Level::info, "fourth", "d");
        const auto lines = lines_of(console.str());
        REQUIRE(lines.size() == 5);
        CHECK(json::parse(lines[3])["event"] == "log_reopen_failed");
        CHECK(json::parse(lines[3])["error"] == "No such file or directory");
        CHECK(json::parse(lines[4])["event"] == "fourth");

        std::filesystem::create_directory(dir.path);
        CHECK(logger.reopen());
        logger.write(log::Level::info, "fifth", "e");
        const auto again = lines_of(read_file(file));
        REQUIRE(again.size() == 1);
        CHECK(json::parse(again[0])["event"] == "fifth");
    }
}

TEST_CASE("a log file that cannot be opened is a startup error", "[logging]") {
    std::ostringstream console;
    log::Logger logger({}, console);
    CHECK_THROWS_WITH(
        logger.configure({log::Level::info, log::Format::json, "/nonexistent-dir/gimbald.log"}),
        "cannot open log file /nonexistent-dir/gimbald.log: No such file or directory");
    // The previous settings stay in force.
    logger.write(log::Level::info, "still", "here");
    CHECK(lines_of(console.str()).size() == 1);
}

TEST_CASE("RollUp reports the first occurrence, then one summary per window", "[logging]") {
    const steady_clock::time_point t0{};
    log::RollUp rollup(5s);

    auto first = rollup.hit(t0);
    REQUIRE(first);
    CHECK(first->first);
    CHECK(first->count == 1);

    for (int i = 1; i <= 11; ++i) CHECK_FALSE(rollup.hit(t0 + i * 400ms));  // up to 4.4 s
    CHECK(rollup.pending() == 11);
    CHECK_FALSE(rollup.poll(t0 + 4900ms));

    auto summary = rollup.hit(t0 + 5s);
    REQUIRE(summary);
    CHECK_FALSE(summary->first);
    CHECK(summary->count == 12);
    CHECK(summary->interval_s == Approx(5.0));

    // A straggler is reported by poll() once its window has passed.
    CHECK_FALSE(rollup.hit(t0 + 6s));
    CHECK_FALSE(rollup.poll(t0 + 9s));
    auto trailing = rollup.poll(t0 + 10s);
    REQUIRE(trailing);
    CHECK(trailing->count == 1);
    CHECK(trailing->interval_s == Approx(5.0));

    // After a quiet window the next occurrence is news again.
    CHECK_FALSE(rollup.poll(t0 + 16s));
    auto again = rollup.hit(t0 + 17s);
    REQUIRE(again);
    CHECK(again->first);
    CHECK(rollup.total() == 15);
}

TEST_CASE("RollUp: a quiet window without poll() still resets", "[logging]") {
    const steady_clock::time_point t0{};
    log::RollUp rollup(5s);
    REQUIRE(rollup.hit(t0));
    auto later = rollup.hit(t0 + 60s);
    REQUIRE(later);
    CHECK(later->first);
}

TEST_CASE("RateLimitedLog writes the first occurrence and rolled-up summaries", "[logging]") {
    std::ostringstream out;
    log::Logger logger({}, out, [] { return example_time(); });
    FakeSteadyClock clock;
    log::RateLimitedLog bad_checksums(log::Level::warn, "bad_checksum", "bad checksums", 5s,
                                      clock.function(), &logger);

    bad_checksums.hit("bad checksum from the gimbal", {{"gimbal", "main"}});
    for (int i = 0; i < 11; ++i) {
        clock.now += 400ms;
        bad_checksums.hit("bad checksum from the gimbal", {{"gimbal", "main"}});
    }
    bad_checksums.poll();  // 4.4 s: nothing yet
    clock.now += 600ms;    // 5.0 s
    bad_checksums.hit("bad checksum from the gimbal", {{"gimbal", "main"}});

    auto lines = lines_of(out.str());
    REQUIRE(lines.size() == 2);
    const json first = json::parse(lines[0]);
    CHECK(first["level"] == "warn");
    CHECK(first["event"] == "bad_checksum");
    CHECK(first["msg"] == "bad checksum from the gimbal");
    CHECK(first["count"] == 1);
    CHECK(first["gimbal"] == "main");
    const json summary = json::parse(lines[1]);
    CHECK(summary["msg"] == "12 bad checksums in the last 5 s");
    CHECK(summary["count"] == 12);
    CHECK(summary["interval_s"] == 5.0);
    CHECK(summary["gimbal"] == "main");

    clock.now += 1s;  // 6 s
    bad_checksums.hit("bad checksum from the gimbal", {{"gimbal", "main"}});
    clock.now += 3s;  // 9 s: the window that began with the summary is still open
    bad_checksums.poll();
    CHECK(lines_of(out.str()).size() == 2);
    clock.now += 1s;  // 10 s
    bad_checksums.poll();
    lines = lines_of(out.str());
    REQUIRE(lines.size() == 3);
    CHECK(json::parse(lines[2])["msg"] == "bad checksums: 1 more in the last 5 s");
    CHECK(bad_checksums.total() == 14);
}

TEST_CASE("repeated lines: 10 a second per event and source, then one summary per 10 s",
          "[logging][rollup]") {
    // Contract section 14 (v4): a flood of `mavlink_refused` wrote 63,811 lines in 40 s.
    std::ostringstream out;
    FakeSteadyClock clock;
    log::Logger logger(
        {}, out, [] { return example_time(); }, clock.function());
    const auto refused = [&](const char* src, int n) {
        for (int i = 0; i < n; ++i)
            logger.write(log::Level::info, "mavlink_refused", "out of range",
                         {{"src", src}, {"n", i}});
    };
    const auto events = [&] {
        std::vector<json> v;
        for (const auto& line : lines_of(out.str())) v.push_back(json::parse(line));
        return v;
    };

    refused("mavlink:255/190", 500);
    refused("mavlink:254/190", 3);  // another source has its own ten
    logger.write(log::Level::info, "command", "ok", {{"src", "mavlink:255/190"}});
    for (int i = 0; i < 30; ++i)  // never rolled up
        logger.write(log::Level::warn, "audit", "ok", {{"src", "mavlink:255/190"}, {"i", i}});
    auto v = events();
    REQUIRE(v.size() == 10 + 3 + 1 + 30);
    CHECK(v[9]["n"] == 9);
    CHECK(logger.suppressed() == 490);

    // The next second: ten more; the first suppressed line's 10 s are not over yet.
    clock.now += 1s;
    refused("mavlink:255/190", 100);
    v = events();
    REQUIRE(v.size() == 54);
    CHECK(v.back()["n"] == 9);
    for (const auto& e : v) CHECK_FALSE(e.contains("suppressed"));

    // 10 s after the first line was suppressed: the summary comes with the next line...
    clock.now += 9s;
    refused("mavlink:255/190", 1);
    v = events();
    REQUIRE(v.size() == 56);
    const json& summary = v[54];
    CHECK(summary["event"] == "mavlink_refused");
    CHECK(summary["level"] == "info");
    CHECK(summary["suppressed"] == 490 + 90);
    CHECK(summary["interval_s"] == 10.0);
    CHECK(summary["src"] == "mavlink:255/190");
    CHECK(summary["n"] == 99);  // the last suppressed line's fields
    CHECK(summary["msg"].get<std::string>().find("580 more mavlink_refused lines") == 0);
    CHECK(v[55]["n"] == 0);
    CHECK_FALSE(v[55].contains("suppressed"));

    // ...or from poll() when the burst stopped.
    refused("mavlink:255/190", 20);  // 9 more this second, 11 suppressed
    clock.now += 9s;
    logger.poll();
    CHECK(events().size() == 65);
    clock.now += 1s;
    logger.poll();
    v = events();
    REQUIRE(v.size() == 66);
    CHECK(v.back()["suppressed"] == 11);
    logger.poll();
    CHECK(events().size() == 66);  // once
    // At shutdown every count is written, due or not.
    refused("mavlink:255/190", 25);
    logger.poll();
    CHECK(events().size() == 76);
    logger.poll(true);
    v = events();
    REQUIRE(v.size() == 77);
    CHECK(v.back()["suppressed"] == 15);
}

TEST_CASE("the roll-up's key: src, else gimbal; a bounded table", "[logging][rollup]") {
    using T = log::LineRollUp::TimePoint;
    log::LineRollUp r;
    std::vector<log::LineRollUp::Summary> due;
    const T t0{};
    const auto admitted = [&](const json& fields, int n, T at) {
        int written = 0;
        for (int i = 0; i < n; ++i)
            written += r.admit(log::Level::warn, "video_viewer", "m", fields, at, due) ? 1 : 0;
        return written;
    };
    CHECK(admitted({{"gimbal", "a"}}, 20, t0) == 10);
    CHECK(admitted({{"gimbal", "b"}}, 20, t0) == 10);
    CHECK(admitted({{"gimbal", "a"}, {"src", "1.2.3.4:5"}}, 20, t0) == 10);
    CHECK(admitted(json(), 20, t0) == 10);
    // One host reconnecting from new ports is one source; "mavlink:SYS/COMP" is one as is.
    int from_one_host = 0;
    for (int port = 40000; port < 40020; ++port)
        from_one_host += admitted({{"src", "http:10.1.1.1:" + std::to_string(port)}}, 1, t0);
    CHECK(from_one_host == 10);
    from_one_host = 0;
    for (int port = 40000; port < 40020; ++port)
        from_one_host += admitted({{"src", "[::1]:" + std::to_string(port)}}, 1, t0);
    CHECK(from_one_host == 10);
    CHECK(admitted({{"src", "mavlink:255/190"}}, 20, t0) == 10);
    CHECK(admitted({{"src", "mavlink:255/191"}}, 20, t0) == 10);
    CHECK(log::LineRollUp::exempt("laser_deadman"));
    CHECK(log::LineRollUp::exempt("laser_fire"));
    CHECK_FALSE(log::LineRollUp::exempt("mavlink_refused"));
    // Sources come from the network: past max_keys they share one count per event.
    for (std::size_t i = 0; i < 2 * log::LineRollUp::max_keys; ++i)
        admitted(
            {{"src", "10.0." + std::to_string(i / 256) + "." + std::to_string(i % 256) + ":5000"}},
            1, t0);
    CHECK(r.keys() <= log::LineRollUp::max_keys + 1);       // and the shared "*"
    CHECK(admitted({{"src", "10.0.9.9:1"}}, 20, t0) == 0);  // "*" had its ten already
    // Quiet sources are forgotten once they have nothing to report.
    r.poll(t0 + 30s, due);
    CHECK(r.keys() == 0);
    CHECK(due.size() == 9);  // a, b, 1.2.3.4, none, 10.1.1.1, [::1], the two mavlink, "*"
    CHECK(admitted({{"gimbal", "a"}}, 20, t0 + 31s) == 10);
}

}  // namespace logging_test
