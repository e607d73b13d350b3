#include "subscriptions.hpp"

#include <algorithm>
#include <cmath>

namespace gimbald {

Subscriptions::Result Subscriptions::subscribe(const Endpoint& who, Subscription s, double now_s) {
    auto it = subs_.find(who);
    s.expires_s = now_s + s.ttl_s;
    if (it != subs_.end()) {
        // A renewal keeps the state cadence running rather than restarting it.
        s.next_state_s = std::min(it->second.next_state_s, now_s + 1.0 / s.rate_hz);
        it->second = s;
        return Result::renewed;
    }
    if (subs_.size() >= max_) return Result::full;
    if (host_count(who.address()) >= max_per_host_) return Result::host_full;
    s.next_state_s = now_s;  // the first STATE goes out at once
    subs_.emplace(who, s);
    return Result::added;
}

std::size_t Subscriptions::host_count(const boost::asio::ip::address& address) const {
    std::size_t n = 0;
    for (const auto& [who, s] : subs_)
        if (who.address() == address) ++n;
    return n;
}

bool Subscriptions::unsubscribe(const Endpoint& who) {
    return subs_.erase(who) != 0;
}

std::vector<Subscriptions::Endpoint> Subscriptions::expire(double now_s) {
    std::vector<Endpoint> gone;
    for (auto it = subs_.begin(); it != subs_.end();) {
        if (it->second.expires_s <= now_s) {
            gone.push_back(it->first);
            it = subs_.erase(it);
        } else {
            ++it;
        }
    }
    return gone;
}

std::vector<Subscriptions::Endpoint> Subscriptions::due_state(const std::string& gimbal,
                                                              double now_s) const {
    std::vector<Endpoint> due;
    for (const auto& [who, s] : subs_)
        if (covers(s, gimbal) && s.next_state_s <= now_s) due.push_back(who);
    return due;
}

const Subscription* Subscriptions::find(const Endpoint& who) const {
    const auto it = subs_.find(who);
    return it == subs_.end() ? nullptr : &it->second;
}

void Subscriptions::mark_sent(double now_s) {
    for (auto& [who, s] : subs_) {
        if (s.next_state_s > now_s) continue;
        // The next multiple of the period: subscribers of one rate then fall due together and
        // share one snapshot, and after a stall the missed datagrams are skipped, not burst.
        const double period = 1.0 / s.rate_hz;
        s.next_state_s = (std::floor(now_s / period + 1e-6) + 1.0) * period;
    }
}

Subscription* Subscriptions::find(const Endpoint& who) {
    const auto it = subs_.find(who);
    return it == subs_.end() ? nullptr : &it->second;
}

std::vector<Subscriptions::Endpoint> Subscriptions::event_targets(const std::string& gimbal) const {
    std::vector<Endpoint> out;
    for (const auto& [who, s] : subs_)
        if (s.events && covers(s, gimbal)) out.push_back(who);
    return out;
}

std::optional<double> Subscriptions::next_due() const {
    std::optional<double> next;
    for (const auto& [who, s] : subs_) {
        const double t = std::min(s.next_state_s, s.expires_s);
        if (!next || t < *next) next = t;
    }
    return next;
}

}  // namespace gimbald
