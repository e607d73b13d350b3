// A token bucket per request source (contract section 10, command.rate_limit). A source over
// its rate gets one `rate_limited` reply per second; the rest are dropped silently and only
// counted. Bounded: at most `max_sources` buckets, idle ones forgotten first. Time passed in.
#pragma once

#include <cstddef>
#include <string>
#include <unordered_map>

namespace gimbal::auth {

class RateLimiter {
  public:
    RateLimiter(double rate_hz, double burst, std::size_t max_sources = 4096);

    enum class Decision { admit, limited_reply, limited_silent };
    Decision admit(const std::string& source, double now_s);
    std::size_t sources() const { return buckets_.size(); }

  private:
    struct Bucket {
        double tokens = 0;
        double updated_s = 0;
        double last_reply_s = -1e300;
    };
    void make_room(double now_s);

    double rate_hz_;
    double burst_;
    std::size_t max_sources_;
    std::unordered_map<std::string, Bucket> buckets_;
};

}  // namespace gimbal::auth
