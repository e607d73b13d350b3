// Prometheus text exposition format 0.0.4
// (https://prometheus.io/docs/instrumenting/exposition_formats/): a writer that emits each metric
// family once (HELP, TYPE, then its samples) with label values and help text escaped, and numbers
// in the format's spelling (+Inf, -Inf, NaN). Pure: the caller gathers the values, this only writes
// text.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "metrics/histogram.hpp"

namespace gimbal::metrics {

enum class Type { counter, gauge, histogram };
std::string_view to_string(Type type);

using Labels = std::vector<std::pair<std::string, std::string>>;

// `\` -> `\\`, `"` -> `\"`, newline -> `\n` (label values).
std::string escape_label_value(std::string_view value);
// `\` -> `\\`, newline -> `\n` (HELP text).
std::string escape_help(std::string_view text);
// Shortest text that reads back as the same double; integers without a decimal point;
// "+Inf", "-Inf", "NaN".
std::string format_value(double value);
// [a-zA-Z_:][a-zA-Z0-9_:]* (metric names) / [a-zA-Z_][a-zA-Z0-9_]* (label names).
bool valid_metric_name(std::string_view name);
bool valid_label_name(std::string_view name);

class Exposition {
  public:
    // Starts a family: its HELP and TYPE lines. Samples of it follow until the next family.
    void family(std::string_view name, Type type, std::string_view help);
    // One sample of the current family (counter/gauge). The family's name is used.
    void sample(const Labels& labels, double value);
    // A whole histogram sample set for `labels`: cumulative _bucket lines (le, ending with
    // +Inf), _sum and _count. The current family must be a histogram.
    void histogram(const Labels& labels, const Histogram& histogram);

    const std::string& text() const { return out_; }

  private:
    void line(std::string_view name, const Labels& labels, double value,
              const std::pair<std::string, std::string>* extra = nullptr);
    std::string out_;
    std::string current_;
    Type type_ = Type::gauge;
};

}  // namespace gimbal::metrics
