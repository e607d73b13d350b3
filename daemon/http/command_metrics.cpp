#include "command_metrics.hpp"

namespace gimbald::http {

namespace {
// A client can name any cmd: an unknown one is counted as cmd="unknown", so a stream of
// made-up names cannot grow the series without bound; the cap is a second guard.
constexpr std::size_t max_series = 1000;
}  // namespace

CommandMetrics::CommandMetrics() : durations_(gimbal::metrics::latency_buckets_s()) {}

void CommandMetrics::observe(const CompletedRequest& done) {
    std::pair<std::string, std::string> key{
        done.result == "unknown_cmd" ? std::string("unknown") : done.cmd.value_or("none"),
        done.result};
    auto it = totals_.find(key);
    if (it == totals_.end()) {
        if (totals_.size() >= max_series) key = {"other", done.result};
        it = totals_.emplace(std::move(key), 0).first;
    }
    ++it->second;
    durations_.observe(done.seconds);
}

}  // namespace gimbald::http
