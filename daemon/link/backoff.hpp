// Reconnect delays: exponential from min_s to max_s (doubling per failure) with +-jitter so
// several daemons (or links) do not retry in lock step. Pure: the random source is injected.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <random>
#include <utility>

namespace gimbald {

struct BackoffOptions {
    double min_s = 0.2;
    double max_s = 5.0;
    double jitter = 0.2;  // each delay is base * (1 +- jitter), never above max_s
};

class Backoff {
  public:
    // Returns a uniformly distributed number in [0, 1).
    using Uniform01 = std::function<double()>;

    explicit Backoff(BackoffOptions options) : Backoff(options, std::random_device{}()) {}
    Backoff(BackoffOptions options, std::uint32_t seed) : Backoff(options, seeded_uniform(seed)) {}
    Backoff(BackoffOptions options, Uniform01 uniform01)
        : options_(sanitized(options)), uniform01_(std::move(uniform01)), base_s_(options_.min_s) {}

    // The delay before the next attempt; the following one will be twice as long (up to max).
    double next() {
        const double u = std::clamp(uniform01_(), 0.0, 1.0);
        const double factor = 1.0 + options_.jitter * (2.0 * u - 1.0);
        const double delay = std::clamp(base_s_ * factor, 0.0, options_.max_s);
        base_s_ = std::min(base_s_ * 2.0, options_.max_s);
        return delay;
    }

    // After a successful connect the next failure starts again at min_s.
    void reset() { base_s_ = options_.min_s; }

    // The delay next() would return without jitter.
    double base_s() const { return base_s_; }
    const BackoffOptions& options() const { return options_; }

  private:
    static Uniform01 seeded_uniform(std::uint32_t seed) {
        return [engine = std::mt19937(seed), dist = std::uniform_real_distribution<double>(
                                                 0.0, 1.0)]() mutable { return dist(engine); };
    }
    static BackoffOptions sanitized(BackoffOptions o) {
        o.min_s = std::max(o.min_s, 0.0);
        o.max_s = std::max(o.max_s, o.min_s);
        o.jitter = std::clamp(o.jitter, 0.0, 1.0);
        return o;
    }

    BackoffOptions options_;
    Uniform01 uniform01_;
    double base_s_;
};

}  // namespace gimbald
