// Structured logs (interface contract section 6). Every line is one record: a timestamp, a
// level, a stable snake_case `event` slug, a human message and structured fields. Format
// "json" writes one JSON object per line (for journald, jq and log shippers); "text" is for
// people at a terminal. spdlog carries the lines to stdout and to an optional file that
// reopen() reopens after logrotate moved it (SIGHUP).
//
//   log::info("link_up", "link connected", {{"gimbal", "main"}, {"endpoint", "10.0.0.2:8747"}});
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace spdlog::sinks {
class sink;
}

namespace gimbal::log {

enum class Level { trace, debug, info, warn, error };
enum class Format { json, text };

std::string_view to_string(Level level);
std::string_view to_string(Format format);
std::optional<Level> parse_level(std::string_view name);
std::optional<Format> parse_format(std::string_view name);

using SystemTime = std::chrono::system_clock::time_point;

// One log record; formatting it is pure so the exact output can be tested.
struct Record {
    SystemTime ts;
    Level level = Level::info;
    std::string_view event;
    std::string_view msg;
    const nlohmann::json* fields = nullptr;  // an object, or null for none
};

// 2026-11-21T06:41:50.123456Z
std::string iso8601_utc(SystemTime ts);
// {"ts":"2026-11-21T06:41:50.123456Z","level":"info","event":"link_up","msg":"...","gimbal":"main"}
std::string format_json(const Record& record);
// 2026-11-21 06:41:50.123 INFO  link_up gimbal=main: link connected
std::string format_text(const Record& record);
std::string format_record(const Record& record, Format format);

struct Settings {
    Level level = Level::info;
    Format format = Format::json;
    std::optional<std::string> file;  // also written here when set
};

// Every line but `audit`, `laser_fire`, `laser_deadman` and `command` goes through the roll-up
// of repeated lines (log_rollup.hpp): at most 10 a second per event and source, then one
// summary line with `suppressed` per 10 s.
class Logger {
  public:
    using Clock = std::function<SystemTime()>;
    using SteadyClock = std::function<std::chrono::steady_clock::time_point()>;

    // Lines go to standard output (and the settings' file); when standard output is the
    // systemd journal, records go to it natively instead (journal.hpp).
    explicit Logger(const Settings& settings = {});
    // Lines go to `console` instead of standard output; `clock` stamps them and `steady`
    // times the roll-up (tests).
    Logger(const Settings& settings, std::ostream& console, Clock clock = {},
           SteadyClock steady = {});
    ~Logger();
    Logger(const Logger&) = delete;
    Logger& operator=(const Logger&) = delete;

    // Applies new settings; opens the file. Throws std::runtime_error when the file cannot be
    // opened (a startup error), leaving the previous settings in place.
    void configure(const Settings& settings);
    // Closes and reopens the log file (SIGHUP after logrotate). A failure is logged to the
    // console and retried on the next reopen(); returns false then.
    bool reopen();

    void set_level(Level level);
    Level level() const;
    Format format() const;
    bool enabled(Level level) const;

    void write(Level level, std::string_view event, std::string_view msg,
               const nlohmann::json& fields = {});
    // Writes the roll-up's summaries of bursts that stopped; call about once a second. With
    // `everything` (at shutdown), every count not yet reported.
    void poll(bool everything = false);
    // Lines the roll-up did not write, since the start.
    std::uint64_t suppressed() const;

  private:
    Logger(const Settings& settings, std::shared_ptr<spdlog::sinks::sink> console, Clock clock,
           SteadyClock steady);

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The process-wide logger the free functions below write to (stdout, info, json until
// configure() is called).
Logger& logger();
void configure(const Settings& settings);
bool reopen();
bool enabled(Level level);
void poll(bool everything = false);  // logger().poll()

inline void write(Level level, std::string_view event, std::string_view msg,
                  const nlohmann::json& fields = {}) {
    logger().write(level, event, msg, fields);
}
inline void trace(std::string_view event, std::string_view msg, const nlohmann::json& fields = {}) {
    write(Level::trace, event, msg, fields);
}
inline void debug(std::string_view event, std::string_view msg, const nlohmann::json& fields = {}) {
    write(Level::debug, event, msg, fields);
}
inline void info(std::string_view event, std::string_view msg, const nlohmann::json& fields = {}) {
    write(Level::info, event, msg, fields);
}
inline void warn(std::string_view event, std::string_view msg, const nlohmann::json& fields = {}) {
    write(Level::warn, event, msg, fields);
}
inline void error(std::string_view event, std::string_view msg, const nlohmann::json& fields = {}) {
    write(Level::error, event, msg, fields);
}

// Roll-up of a repeated event, pure: the first occurrence is reported at once, later ones
// are counted and reported as one summary per window. Time is passed in.
class RollUp {
  public:
    using TimePoint = std::chrono::steady_clock::time_point;
    struct Report {
        bool first = false;       // the first occurrence (count is 1)
        std::uint64_t count = 0;  // occurrences this report covers
        double interval_s = 0;    // seconds those occurrences span (summaries)
    };

    explicit RollUp(std::chrono::steady_clock::duration window = std::chrono::seconds(5))
        : window_(window) {}

    // One occurrence at `now`; returns what to log, if anything.
    std::optional<Report> hit(TimePoint now);
    // Call from time to time (e.g. on a 1 s timer): reports occurrences still counted once
    // their window has passed, so a burst that stops is not left unreported.
    std::optional<Report> poll(TimePoint now);

    std::uint64_t total() const { return total_; }
    std::uint64_t pending() const { return pending_; }

  private:
    std::optional<Report> summary(TimePoint now);

    std::chrono::steady_clock::duration window_;
    std::optional<TimePoint> window_start_;  // empty: quiet, the next hit is a "first"
    std::uint64_t pending_ = 0;              // counted since window_start_, not yet reported
    std::uint64_t total_ = 0;
};

// A RollUp that writes its reports: the first occurrence with the caller's message, then
// summaries such as "12 bad checksums in the last 5 s", each with the latest occurrence's
// fields plus `count` (and `interval_s` for summaries). Clock and logger are injectable.
class RateLimitedLog {
  public:
    using Clock = std::function<RollUp::TimePoint()>;

    // `plural_noun` names the occurrences in summaries: "bad checksums".
    RateLimitedLog(Level level, std::string event, std::string plural_noun,
                   std::chrono::steady_clock::duration window = std::chrono::seconds(5),
                   Clock clock = {}, Logger* target = nullptr);

    void hit(std::string_view msg, const nlohmann::json& fields = {});
    void poll();

    std::uint64_t total() const { return rollup_.total(); }

  private:
    void emit(const RollUp::Report& report, std::string_view msg);

    Level level_;
    std::string event_;
    std::string plural_noun_;
    Clock clock_;
    Logger* target_;
    RollUp rollup_;
    nlohmann::json last_fields_;
};

}  // namespace gimbal::log
