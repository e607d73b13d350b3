// GET /metrics (contract section 11): every gauge and counter of the daemon in the
// Prometheus text format 0.0.4, gathered at scrape time. Names and meanings: docs/http.md.
#pragma once

#include <string>

#include "command_metrics.hpp"
#include "daemon_view.hpp"

namespace gimbald::http {

inline constexpr const char* metrics_content_type = "text/plain; version=0.0.4; charset=utf-8";

std::string render_metrics(const DaemonView& daemon, const CommandMetrics& commands,
                           const HttpStats& http);

}  // namespace gimbald::http
