// Counts every request the one request path completed (RequestPath::add_observer), for
// gimbald_commands_total{cmd,result} and gimbald_command_duration_seconds.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "metrics/histogram.hpp"
#include "request_path.hpp"

namespace gimbald::http {

class CommandMetrics {
  public:
    CommandMetrics();
    void observe(const CompletedRequest& done);

    // (cmd, result) -> count; cmd "none" when the request could not be parsed.
    const std::map<std::pair<std::string, std::string>, std::uint64_t>& totals() const {
        return totals_;
    }
    const gimbal::metrics::Histogram& durations() const { return durations_; }

  private:
    std::map<std::pair<std::string, std::string>, std::uint64_t> totals_;
    gimbal::metrics::Histogram durations_;
};

}  // namespace gimbald::http
