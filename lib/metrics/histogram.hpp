// A Prometheus-style histogram: fixed upper bounds, counts per bucket, sum and count.
#pragma once

#include <cstdint>
#include <vector>

namespace gimbal::metrics {

class Histogram {
  public:
    // `bounds`: the buckets' upper bounds (le), strictly increasing; +Inf is implicit.
    explicit Histogram(std::vector<double> bounds);

    void observe(double value);

    const std::vector<double>& bounds() const { return bounds_; }
    // Observations <= bounds()[i] (cumulative, as Prometheus reports them).
    std::uint64_t cumulative(std::size_t i) const;
    std::uint64_t count() const { return count_; }
    double sum() const { return sum_; }

  private:
    std::vector<double> bounds_;
    std::vector<std::uint64_t> counts_;  // per bucket, not cumulative
    std::uint64_t count_ = 0;
    double sum_ = 0;
};

// Buckets for request latencies of a local daemon: 50 us to 2.5 s.
std::vector<double> latency_buckets_s();

}  // namespace gimbal::metrics
