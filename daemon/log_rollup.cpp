#include "log_rollup.hpp"

#include <fmt/format.h>
#include <cmath>

namespace gimbal::log {

namespace {

using nlohmann::json;

constexpr std::string_view never_rolled_up[] = {"audit", "laser_fire", "laser_deadman", "command"};

// "1.2.3.4:5", "http:1.2.3.4:5", "[::1]:5" -> without ":5": one host reconnecting from new
// ports is one source (a viewer flood came that way); "mavlink:255/190" stays as it is.
std::string_view without_port(std::string_view src) {
    const auto colon = src.rfind(':');
    if (colon == std::string_view::npos || colon + 1 == src.size() || colon == 0) return src;
    const auto port = src.substr(colon + 1);
    if (port.size() > 5 || port.find_first_not_of("0123456789") != std::string_view::npos)
        return src;
    const auto host = src.substr(0, colon);
    if (host.back() == ']') return host;  // [v6]:port
    const auto start = host.rfind(':');
    const auto last = start == std::string_view::npos ? host : host.substr(start + 1);
    const bool ipv4 = !last.empty() &&
                      last.find_first_not_of("0123456789.") == std::string_view::npos &&
                      last.find('.') != std::string_view::npos;
    return ipv4 ? host : src;
}

// `src` (its host) when the line has one, else `gimbal`, else nothing.
std::string_view source_of(const json& fields) {
    if (!fields.is_object()) return {};
    if (const auto it = fields.find("src"); it != fields.end() && it->is_string())
        return without_port(it->get_ref<const std::string&>());
    if (const auto it = fields.find("gimbal"); it != fields.end() && it->is_string())
        return it->get_ref<const std::string&>();
    return {};
}

std::string key_of(std::string_view event, std::string_view source) {
    std::string key(event);
    key += '\0';
    key += source;
    return key;
}

}  // namespace

bool LineRollUp::exempt(std::string_view event) {
    for (const auto e : never_rolled_up)
        if (e == event) return true;
    return false;
}

LineRollUp::Entry& LineRollUp::entry_for(std::string_view event, const json& fields,
                                         TimePoint now) {
    std::string key = key_of(event, source_of(fields));
    auto it = entries_.find(key);
    if (it == entries_.end()) {
        if (entries_.size() >= max_keys) forget_quiet(now);
        if (entries_.size() >= max_keys) key = key_of(event, "*");
        it = entries_.try_emplace(std::move(key)).first;
        if (it->second.event.empty()) {
            it->second.event = std::string(event);
            it->second.window_start = now;
        }
    }
    return it->second;
}

bool LineRollUp::admit(Level level, std::string_view event, std::string_view msg,
                       const json& fields, TimePoint now, std::vector<Summary>& due) {
    if (exempt(event)) return true;
    Entry& e = entry_for(event, fields, now);
    e.last_seen = now;
    if (e.suppressed > 0 && now - e.suppressed_since >= summary_every) summarise(e, now, due);
    if (now - e.window_start >= std::chrono::seconds(1)) {
        e.window_start = now;
        e.in_window = 0;
    }
    if (e.in_window < lines_per_second) {
        ++e.in_window;
        return true;
    }
    if (e.suppressed++ == 0) e.suppressed_since = now;
    ++suppressed_total_;
    e.last_level = level;
    e.last_msg = std::string(msg);
    e.last_fields = fields.is_object() ? fields : json::object();
    return false;
}

void LineRollUp::poll(TimePoint now, std::vector<Summary>& due) {
    for (auto& [key, e] : entries_)
        if (e.suppressed > 0 && now - e.suppressed_since >= summary_every) summarise(e, now, due);
    forget_quiet(now);
}

void LineRollUp::flush(TimePoint now, std::vector<Summary>& due) {
    for (auto& [key, e] : entries_)
        if (e.suppressed > 0) summarise(e, now, due);
}

void LineRollUp::summarise(Entry& e, TimePoint now, std::vector<Summary>& due) {
    // Tenths of a second: "in the last 10.3 s".
    const double interval =
        std::round(std::chrono::duration<double>(now - e.suppressed_since).count() * 10.0) / 10.0;
    json fields = std::move(e.last_fields);
    fields["suppressed"] = e.suppressed;
    fields["interval_s"] = interval;
    due.push_back(
        Summary{e.last_level, e.event,
                fmt::format("{} more {} lines in the last {:g} s, not written (more "
                            "than {} a second); the last: {}",
                            e.suppressed, e.event, interval, lines_per_second, e.last_msg),
                std::move(fields)});
    e.suppressed = 0;
    e.last_fields = json();
    e.last_msg.clear();
}

void LineRollUp::forget_quiet(TimePoint now) {
    // A source silent for a whole summary period with nothing left to report starts afresh.
    std::erase_if(entries_, [now](const auto& item) {
        const Entry& e = item.second;
        return e.suppressed == 0 && now - e.last_seen >= summary_every;
    });
}

}  // namespace gimbal::log
