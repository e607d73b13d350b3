// The roll-up of repeated log lines (contract section 14, v4): lines of one event and source
// (`src` - its host, a port left out - or `gimbal` when a line has no `src`) are written at
// most 10 a second; the rest are
// counted, and one summary line with `"suppressed": N` follows per 10 s. A flood of refused
// MAVLink commands or video viewers then cannot push journald into its rate limit and so cost
// the lines that matter: `audit`, `laser_fire`, `laser_deadman` and `command` are never rolled
// up. Pure: time is passed in; the Logger (logging.hpp) applies it to every line it writes.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "logging.hpp"

namespace gimbal::log {

class LineRollUp {
  public:
    using TimePoint = std::chrono::steady_clock::time_point;

    static constexpr std::size_t lines_per_second = 10;
    static constexpr std::chrono::seconds summary_every{10};
    // Sources come from the network (addresses): past this many keys, an event's further
    // sources share one count, source "*" (one more key per event).
    static constexpr std::size_t max_keys = 256;

    // A summary to write: the last suppressed line's level, event and fields plus
    // `suppressed` (how many were not written) and `interval_s` (since the first of them).
    struct Summary {
        Level level;
        std::string event;
        std::string msg;
        nlohmann::json fields;
    };

    // Never rolled up.
    static bool exempt(std::string_view event);

    // One line at `now`: true to write it. Summaries that fell due first are appended to `due`
    // (write them before the line).
    bool admit(Level level, std::string_view event, std::string_view msg,
               const nlohmann::json& fields, TimePoint now, std::vector<Summary>& due);
    // Summaries of bursts that stopped, once their 10 s have passed; forgets quiet sources.
    // Call about once a second.
    void poll(TimePoint now, std::vector<Summary>& due);
    // Every count not yet reported, due or not (at shutdown).
    void flush(TimePoint now, std::vector<Summary>& due);

    std::size_t keys() const { return entries_.size(); }
    std::uint64_t suppressed_total() const { return suppressed_total_; }

  private:
    struct Entry {
        TimePoint window_start{};      // the current one-second window
        std::size_t in_window = 0;     // lines written in it
        std::uint64_t suppressed = 0;  // not written since suppressed_since
        TimePoint suppressed_since{};
        TimePoint last_seen{};
        Level last_level = Level::info;
        std::string event;
        std::string last_msg;
        nlohmann::json last_fields;
    };

    Entry& entry_for(std::string_view event, const nlohmann::json& fields, TimePoint now);
    static void summarise(Entry& e, TimePoint now, std::vector<Summary>& due);
    void forget_quiet(TimePoint now);

    std::map<std::string, Entry, std::less<>> entries_;  // by event '\0' source
    std::uint64_t suppressed_total_ = 0;
};

}  // namespace gimbal::log
