#include "auth/rate_limiter.hpp"

#include <algorithm>

namespace gimbal::auth {

RateLimiter::RateLimiter(double rate_hz, double burst, std::size_t max_sources)
    : rate_hz_(rate_hz),
      burst_(std::max(burst, 1.0)),
      max_sources_(std::max<std::size_t>(max_sources, 1)) {}

void RateLimiter::make_room(double now_s) {
    // A bucket that has refilled completely holds no memory worth keeping.
    for (auto it = buckets_.begin(); it != buckets_.end();) {
        const double tokens = it->second.tokens + (now_s - it->second.updated_s) * rate_hz_;
        it = tokens >= burst_ ? buckets_.erase(it) : std::next(it);
    }
    if (buckets_.size() < max_sources_) return;
    // Still full (a flood from many sources): forget the least recently seen.
    auto oldest = std::min_element(
        buckets_.begin(), buckets_.end(),
        [](const auto& a, const auto& b) { return a.second.updated_s < b.second.updated_s; });
    buckets_.erase(oldest);
}

RateLimiter::Decision RateLimiter::admit(const std::string& source, double now_s) {
    auto it = buckets_.find(source);
    if (it == buckets_.end()) {
        if (buckets_.size() >= max_sources_) make_room(now_s);
        it = buckets_.emplace(source, Bucket{burst_, now_s, -1e300}).first;
    }
    Bucket& b = it->second;
    b.tokens = std::min(burst_, b.tokens + std::max(0.0, now_s - b.updated_s) * rate_hz_);
    b.updated_s = now_s;
    if (b.tokens >= 1.0) {
        b.tokens -= 1.0;
        return Decision::admit;
    }
    if (now_s - b.last_reply_s >= 1.0) {
        b.last_reply_s = now_s;
        return Decision::limited_reply;
    }
    return Decision::limited_silent;
}

}  // namespace gimbal::auth
