#include "journal.hpp"

#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>

// CODE_FILE, CODE_LINE and CODE_FUNC would name this file, not the code that logged.
#define SD_JOURNAL_SUPPRESS_LOCATION
#include <systemd/sd-journal.h>

#include <array>
#include <charconv>
#include <cstdlib>

namespace gimbal::log {

namespace {

using nlohmann::json;

// Fields journald or journalctl read a meaning into: a log key of that name is prefixed.
constexpr std::array<std::string_view, 21> reserved_names{"MESSAGE",
                                                          "MESSAGE_ID",
                                                          "PRIORITY",
                                                          "CODE_FILE",
                                                          "CODE_LINE",
                                                          "CODE_FUNC",
                                                          "ERRNO",
                                                          "INVOCATION_ID",
                                                          "USER_INVOCATION_ID",
                                                          "SYSLOG_FACILITY",
                                                          "SYSLOG_IDENTIFIER",
                                                          "SYSLOG_PID",
                                                          "SYSLOG_TIMESTAMP",
                                                          "SYSLOG_RAW",
                                                          "DOCUMENTATION",
                                                          "TID",
                                                          "UNIT",
                                                          "USER_UNIT",
                                                          "OBJECT_PID",
                                                          "COREDUMP_UNIT",
                                                          "COREDUMP_USER_UNIT"};

constexpr std::size_t max_field_name = 64;  // journald's limit
// Where sd_journal_sendv() sends (libsystemd's fixed path). It reports success when the
// socket is missing ("fail silently"), so its presence is checked first.
constexpr const char* journal_socket = "/run/systemd/journal/socket";

bool parse_number(std::string_view text, unsigned long long& out) {
    const auto* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, out);
    return ec == std::errc() && ptr == end && !text.empty();
}

std::string field_value(const json& value) {
    if (value.is_string()) return value.get<std::string>();
    return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

bool is_simple(const json& value) {
    return value.is_string() || value.is_number() || value.is_boolean();
}

void add(std::vector<std::string>& out, std::string_view key, const json& value) {
    if (!is_simple(value)) return;
    const std::string name = journal_field_name(key);
    if (name.empty()) return;
    out.push_back(name + "=" + field_value(value));
}

}  // namespace

bool journal_stream_matches(std::string_view journal_stream, unsigned long long device,
                            unsigned long long inode) {
    const auto colon = journal_stream.find(':');
    if (colon == std::string_view::npos) return false;
    unsigned long long d = 0;
    unsigned long long i = 0;
    return parse_number(journal_stream.substr(0, colon), d) &&
           parse_number(journal_stream.substr(colon + 1), i) && d == device && i == inode;
}

bool stdout_is_journal() {
    const char* stream = std::getenv("JOURNAL_STREAM");
    if (stream == nullptr) return false;
    struct stat st {};
    if (::fstat(STDOUT_FILENO, &st) != 0) return false;
    return journal_stream_matches(stream, static_cast<unsigned long long>(st.st_dev),
                                  static_cast<unsigned long long>(st.st_ino));
}

int journal_priority(Level level) {
    switch (level) {
        case Level::error:
            return 3;
        case Level::warn:
            return 4;
        case Level::info:
            return 6;
        case Level::debug:
        case Level::trace:
            return 7;
    }
    return 6;
}

std::string journal_field_name(std::string_view key) {
    std::string name;
    name.reserve(key.size());
    for (const char c : key) {
        if (c >= 'a' && c <= 'z')
            name.push_back(static_cast<char>(c - 'a' + 'A'));
        else if ((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))
            name.push_back(c);
        else
            name.push_back('_');
    }
    bool prefix =
        name.empty() || name.front() == '_' || (name.front() >= '0' && name.front() <= '9');
    for (const auto reserved : reserved_names) prefix = prefix || name == reserved;
    if (prefix) name = "GIMBALD_" + name;
    if (name.size() > max_field_name) return {};
    return name;
}

std::vector<std::string> journal_fields(const Record& record, std::string_view line) {
    std::vector<std::string> out;
    out.push_back("MESSAGE=" + std::string(line));
    out.push_back("PRIORITY=" + std::to_string(journal_priority(record.level)));
    out.push_back("SYSLOG_IDENTIFIER=gimbald");
    add(out, "ts", json(iso8601_utc(record.ts)));
    add(out, "level", json(to_string(record.level)));
    add(out, "event", json(record.event));
    add(out, "msg", json(record.msg));
    if (record.fields != nullptr && record.fields->is_object()) {
        for (const auto& [key, value] : record.fields->items()) {
            // As in the JSON line: a field named like one of the record's own keys is renamed.
            const bool own = key == "ts" || key == "level" || key == "event" || key == "msg";
            add(out, own ? "field_" + key : key, value);
        }
    }
    return out;
}

bool send_to_journal(const std::vector<std::string>& fields) {
    struct stat st {};
    if (::stat(journal_socket, &st) != 0 || !S_ISSOCK(st.st_mode)) return false;
    std::vector<struct iovec> iov(fields.size());
    for (std::size_t i = 0; i < fields.size(); ++i) {
        iov[i].iov_base = const_cast<char*>(fields[i].data());
        iov[i].iov_len = fields[i].size();
    }
    return sd_journal_sendv(iov.data(), static_cast<int>(iov.size())) >= 0;
}

}  // namespace gimbal::log
