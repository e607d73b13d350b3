#include "logging.hpp"

#include <spdlog/details/log_msg.h>
#include <spdlog/logger.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/sinks/stdout_sinks.h>

#include <fmt/format.h>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "journal.hpp"
#include "log_rollup.hpp"

namespace gimbal::log {

namespace {

using nlohmann::json;

constexpr std::string_view level_names[] = {"trace", "debug", "info", "warn", "error"};
constexpr std::string_view level_labels[] = {"TRACE", "DEBUG", "INFO ", "WARN ", "ERROR"};

std::size_t index_of(Level level) {
    return static_cast<std::size_t>(level);
}

spdlog::level::level_enum to_spdlog(Level level) {
    switch (level) {
        case Level::trace:
            return spdlog::level::trace;
        case Level::debug:
            return spdlog::level::debug;
        case Level::info:
            return spdlog::level::info;
        case Level::warn:
            return spdlog::level::warn;
        case Level::error:
            return spdlog::level::err;
    }
    return spdlog::level::info;
}

// Text from anywhere (wire strings, file names) must not break the one-line-JSON rule.
std::string dump(const json& value) {
    return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

bool is_reserved_key(std::string_view key) {
    return key == "ts" || key == "level" || key == "event" || key == "msg";
}

// A string value that reads unambiguously without quotes in the text format.
bool is_bare_word(std::string_view s) {
    if (s.empty()) return false;
    for (char c : s) {
        if (c <= ' ' || c > '~' || c == '"' || c == '=' || c == '\\') return false;
    }
    return true;
}

// Control characters (C0, DEL and, in UTF-8, C1) as escapes, so no text from a request can
// end a line or forge the start of another; with `backslash`, a backslash is doubled too so
// an escape in the output is never ambiguous. JSON text (dump()) has its C0 characters and
// backslashes escaped already, but not DEL and C1.
void append_escaped(std::string& out, std::string_view text, bool backslash) {
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c == '\\' && backslash) {
            out += "\\\\";
        } else if (c == '\n') {
            out += "\\n";
        } else if (c == '\r') {
            out += "\\r";
        } else if (c == '\t') {
            out += "\\t";
        } else if (c < 0x20 || c == 0x7f) {
            out += fmt::format("\\x{:02x}", c);
        } else if (c == 0xc2 && i + 1 < text.size() &&
                   static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
                   static_cast<unsigned char>(text[i + 1]) <= 0x9f) {
            out += fmt::format("\\u{:04x}", static_cast<unsigned char>(text[++i]));
        } else {
            out += static_cast<char>(c);
        }
    }
}

std::string escaped(std::string_view text) {
    std::string out;
    append_escaped(out, text, true);
    return out;
}

std::string text_value(const json& value) {
    if (value.is_string()) {
        const auto& s = value.get_ref<const std::string&>();
        if (is_bare_word(s)) return s;
    }
    std::string out;
    append_escaped(out, dump(value), false);
    return out;
}

struct BrokenDownTime {
    std::tm tm{};
    long long micros = 0;
};

BrokenDownTime break_down(SystemTime ts) {
    using namespace std::chrono;
    const auto since_epoch = duration_cast<microseconds>(ts.time_since_epoch());
    const auto whole = floor<seconds>(since_epoch);
    BrokenDownTime out;
    out.micros = (since_epoch - whole).count();
    const std::time_t t = static_cast<std::time_t>(whole.count());
    gmtime_r(&t, &out.tm);
    return out;
}

// Appends to a file opened in append mode; reopen() opens the path again so logrotate can
// move the old file away. Single-threaded: Logger serialises all writes.
class ReopenableFileSink final : public spdlog::sinks::base_sink<spdlog::details::null_mutex> {
  public:
    explicit ReopenableFileSink(std::string path) : path_(std::move(path)) {
        if (!open()) {
            throw std::runtime_error(
                fmt::format("cannot open log file {}: {}", path_, last_error_));
        }
    }
    ~ReopenableFileSink() override { close(); }

    const std::string& path() const { return path_; }
    const std::string& last_error() const { return last_error_; }

    bool reopen() {
        close();
        return open();
    }

  protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {
        if (file_ == nullptr) return;  // reopen failed; the console still has the line
        spdlog::memory_buf_t line;
        formatter_->format(msg, line);
        std::fwrite(line.data(), 1, line.size(), file_);
        std::fflush(file_);
    }
    void flush_() override {
        if (file_ != nullptr) std::fflush(file_);
    }

  private:
    bool open() {
        file_ = std::fopen(path_.c_str(), "ae");
        if (file_ == nullptr) last_error_ = std::strerror(errno);
        return file_ != nullptr;
    }
    void close() {
        if (file_ != nullptr) std::fclose(file_);
        file_ = nullptr;
    }

    std::string path_;
    std::string last_error_;
    std::FILE* file_ = nullptr;
};

}  // namespace

std::string_view to_string(Level level) {
    return level_names[index_of(level)];
}

std::string_view to_string(Format format) {
    return format == Format::json ? "json" : "text";
}

std::optional<Level> parse_level(std::string_view name) {
    for (std::size_t i = 0; i < std::size(level_names); ++i) {
        if (level_names[i] == name) return static_cast<Level>(i);
    }
    return std::nullopt;
}

std::optional<Format> parse_format(std::string_view name) {
    if (name == "json") return Format::json;
    if (name == "text") return Format::text;
    return std::nullopt;
}

std::string iso8601_utc(SystemTime ts) {
    const auto t = break_down(ts);
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:06}Z", t.tm.tm_year + 1900,
                       t.tm.tm_mon + 1, t.tm.tm_mday, t.tm.tm_hour, t.tm.tm_min, t.tm.tm_sec,
                       t.micros);
}

std::string format_json(const Record& record) {
    std::string line =
        fmt::format(R"({{"ts":"{}","level":"{}","event":{},"msg":{})", iso8601_utc(record.ts),
                    to_string(record.level), dump(json(record.event)), dump(json(record.msg)));
    if (record.fields != nullptr && record.fields->is_object()) {
        for (const auto& [key, value] : record.fields->items()) {
            // A field must not shadow the record's own keys: keep it, renamed.
            const std::string name = is_reserved_key(key) ? "field_" + key : key;
            line += ',';
            line += dump(json(name));
            line += ':';
            line += dump(value);
        }
    } else if (record.fields != nullptr && !record.fields->is_null()) {
        line += ",\"fields\":" + dump(*record.fields);
    }
    line += '}';
    return line;
}

std::string format_text(const Record& record) {
    const auto t = break_down(record.ts);
    std::string line =
        fmt::format("{:04}-{:02}-{:02} {:02}:{:02}:{:02}.{:03} {} {}", t.tm.tm_year + 1900,
                    t.tm.tm_mon + 1, t.tm.tm_mday, t.tm.tm_hour, t.tm.tm_min, t.tm.tm_sec,
                    t.micros / 1000, level_labels[index_of(record.level)], escaped(record.event));
    if (record.fields != nullptr && record.fields->is_object()) {
        for (const auto& [key, value] : record.fields->items()) {
            line += fmt::format(" {}={}", escaped(key), text_value(value));
        }
    } else if (record.fields != nullptr && !record.fields->is_null()) {
        line += " fields=";
        append_escaped(line, dump(*record.fields), false);
    }
    if (!record.msg.empty()) {
        line += ": ";
        append_escaped(line, record.msg, true);
    }
    return line;
}

std::string format_record(const Record& record, Format format) {
    return format == Format::json ? format_json(record) : format_text(record);
}

struct Logger::Impl {
    mutable std::mutex mutex;
    Settings settings;
    Clock clock;
    SteadyClock steady;
    LineRollUp rollup;
    std::vector<LineRollUp::Summary> due;  // reused: no allocation per line
    spdlog::sink_ptr console;
    bool journal = false;  // standard output is the journal: records go to it natively
    std::shared_ptr<ReopenableFileSink> file;
    std::shared_ptr<spdlog::logger> transport;

    Impl(spdlog::sink_ptr console_sink, Clock c, SteadyClock s)
        : clock(c ? std::move(c) : Clock(&std::chrono::system_clock::now)),
          steady(s ? std::move(s) : SteadyClock(&std::chrono::steady_clock::now)),
          console(std::move(console_sink)) {
        console->set_pattern("%v");  // lines are formatted by format_record()
        rebuild_transport();
    }

    void rebuild_transport() {
        std::vector<spdlog::sink_ptr> sinks{console};
        if (file) sinks.push_back(file);
        transport = std::make_shared<spdlog::logger>("gimbald", sinks.begin(), sinks.end());
        transport->set_level(to_spdlog(settings.level));
        transport->flush_on(spdlog::level::trace);
    }

    void apply(const Settings& next) {
        std::shared_ptr<ReopenableFileSink> next_file;
        if (next.file) {
            next_file = (file && file->path() == *next.file)
                            ? file
                            : std::make_shared<ReopenableFileSink>(*next.file);
            next_file->set_pattern("%v");
        }
        file = std::move(next_file);
        settings = next;
        rebuild_transport();
    }

    void write_locked(Level level, std::string_view event, std::string_view msg,
                      const json& fields) {
        const Record record{clock(), level, event, msg, &fields};
        const std::string line = format_record(record, settings.format);
        const spdlog::string_view_t text(line.data(), line.size());
        if (journal && send_to_journal(journal_fields(record, line))) {
            // Journaled: only the file still needs the line. Else (journald unreachable)
            // standard output has it, as without a journal.
            if (file) file->log(spdlog::details::log_msg("gimbald", to_spdlog(level), text));
            return;
        }
        transport->log(to_spdlog(level), text);
    }

    void write_due() {
        for (const auto& s : due) write_locked(s.level, s.event, s.msg, s.fields);
        due.clear();
    }
};

Logger::Logger(const Settings& settings)
    : Logger(settings, std::make_shared<spdlog::sinks::stdout_sink_st>(), Clock{}, SteadyClock{}) {
    impl_->journal = stdout_is_journal();
}

Logger::Logger(const Settings& settings, std::ostream& console, Clock clock, SteadyClock steady)
    : Logger(settings, std::make_shared<spdlog::sinks::ostream_sink_st>(console, true),
             std::move(clock), std::move(steady)) {}

Logger::Logger(const Settings& settings, std::shared_ptr<spdlog::sinks::sink> console, Clock clock,
               SteadyClock steady)
    : impl_(std::make_unique<Impl>(std::move(console), std::move(clock), std::move(steady))) {
    configure(settings);
}

Logger::~Logger() = default;

void Logger::configure(const Settings& settings) {
    std::lock_guard lock(impl_->mutex);
    impl_->apply(settings);
}

bool Logger::reopen() {
    std::lock_guard lock(impl_->mutex);
    if (!impl_->file) return true;
    if (impl_->file->reopen()) return true;
    const json fields = {{"file", impl_->file->path()}, {"error", impl_->file->last_error()}};
    impl_->write_locked(Level::error, "log_reopen_failed", "cannot reopen the log file", fields);
    return false;
}

void Logger::set_level(Level level) {
    std::lock_guard lock(impl_->mutex);
    impl_->settings.level = level;
    impl_->transport->set_level(to_spdlog(level));
}

Level Logger::level() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->settings.level;
}

Format Logger::format() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->settings.format;
}

bool Logger::enabled(Level level) const {
    std::lock_guard lock(impl_->mutex);
    return level >= impl_->settings.level;
}

void Logger::write(Level level, std::string_view event, std::string_view msg, const json& fields) {
    std::lock_guard lock(impl_->mutex);
    if (level < impl_->settings.level) return;
    const bool admitted =
        impl_->rollup.admit(level, event, msg, fields, impl_->steady(), impl_->due);
    impl_->write_due();
    if (admitted) impl_->write_locked(level, event, msg, fields);
}

void Logger::poll(bool everything) {
    std::lock_guard lock(impl_->mutex);
    if (everything)
        impl_->rollup.flush(impl_->steady(), impl_->due);
    else
        impl_->rollup.poll(impl_->steady(), impl_->due);
    impl_->write_due();
}

std::uint64_t Logger::suppressed() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->rollup.suppressed_total();
}

Logger& logger() {
    static Logger instance;
    return instance;
}

void configure(const Settings& settings) {
    logger().configure(settings);
}
bool reopen() {
    return logger().reopen();
}
bool enabled(Level level) {
    return logger().enabled(level);
}
void poll(bool everything) {
    logger().poll(everything);
}

std::optional<RollUp::Report> RollUp::hit(TimePoint now) {
    ++total_;
    if (window_start_ && pending_ == 0 && now - *window_start_ >= window_) {
        window_start_.reset();  // quiet for a whole window: this one is news again
    }
    if (!window_start_) {
        window_start_ = now;
        return Report{true, 1, 0.0};
    }
    ++pending_;
    return summary(now);
}

std::optional<RollUp::Report> RollUp::poll(TimePoint now) {
    if (!window_start_) return std::nullopt;
    if (pending_ == 0) {
        // A whole window without a repeat: the next occurrence is news again.
        if (now - *window_start_ >= window_) window_start_.reset();
        return std::nullopt;
    }
    return summary(now);
}

std::optional<RollUp::Report> RollUp::summary(TimePoint now) {
    const auto elapsed = now - *window_start_;
    if (elapsed < window_) return std::nullopt;
    Report report{false, pending_, std::chrono::duration<double>(elapsed).count()};
    pending_ = 0;
    window_start_ = now;
    return report;
}

RateLimitedLog::RateLimitedLog(Level level, std::string event, std::string plural_noun,
                               std::chrono::steady_clock::duration window, Clock clock,
                               Logger* target)
    : level_(level),
      event_(std::move(event)),
      plural_noun_(std::move(plural_noun)),
      clock_(clock ? std::move(clock) : Clock(&std::chrono::steady_clock::now)),
      target_(target),
      rollup_(window) {}

void RateLimitedLog::hit(std::string_view msg, const json& fields) {
    last_fields_ = fields.is_object() ? fields : json::object();
    if (const auto report = rollup_.hit(clock_())) emit(*report, msg);
}

void RateLimitedLog::poll() {
    if (const auto report = rollup_.poll(clock_())) emit(*report, {});
}

void RateLimitedLog::emit(const RollUp::Report& report, std::string_view msg) {
    Logger& out = target_ != nullptr ? *target_ : logger();
    json fields = last_fields_;
    fields["count"] = report.count;
    if (report.first) {
        out.write(level_, event_, msg.empty() ? std::string_view(plural_noun_) : msg, fields);
        return;
    }
    // Tenths of a second are plenty for "in the last 5 s".
    const double interval = std::round(report.interval_s * 10.0) / 10.0;
    fields["interval_s"] = interval;
    const std::string summary =
        report.count == 1
            ? fmt::format("{}: 1 more in the last {:g} s", plural_noun_, interval)
            : fmt::format("{} {} in the last {:g} s", report.count, plural_noun_, interval);
    out.write(level_, event_, summary, fields);
}

}  // namespace gimbal::log
