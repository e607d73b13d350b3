// Subscribers of the command socket (contract section 4.1, subscribe/unsubscribe): who gets
// STATE at which rate and events, until their TTL passes without a renewal. Time is passed
// in, so the table is tested without sockets or clocks.
#pragma once

#include <boost/asio/ip/udp.hpp>
#include <chrono>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "state/state_push.hpp"

namespace gimbald {

// The clock of the subscriber table: steady seconds, the same for every caller.
inline double steady_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

struct Subscription {
    std::optional<std::string> gimbal;  // nullopt: every gimbal
    double rate_hz = 10.0;
    double ttl_s = 60.0;
    bool events = true;
    gimbal::state::StreamOptions stream;  // keys, changes, full_every_s
    std::optional<std::string> key_id;    // signed subscription: pushes are signed with this key
    // With stream.changes: what this subscriber last got of each gimbal. A renewal starts
    // afresh, so the first push after every subscribe is a full STATE.
    std::map<std::string, gimbal::state::DeltaCursor> cursors;
    double expires_s = 0;
    double next_state_s = 0;
};

class Subscriptions {
  public:
    using Endpoint = boost::asio::ip::udp::endpoint;

    // At most `max_subscribers` in all and `max_per_host` from one source address
    // (command.max_subscribers, command.max_subscribers_per_host).
    explicit Subscriptions(std::size_t max_subscribers, std::size_t max_per_host = 16)
        : max_(max_subscribers), max_per_host_(max_per_host) {}

    enum class Result { added, renewed, full, host_full };
    // Adds or renews (replacing its parameters) the subscription of `who`. A new one is
    // refused when the table is full, or when `who`'s address already holds max_per_host.
    Result subscribe(const Endpoint& who, Subscription s, double now_s);
    bool unsubscribe(const Endpoint& who);
    // Drops subscriptions whose TTL passed; returns who was dropped.
    std::vector<Endpoint> expire(double now_s);

    // Subscribers due a STATE datagram for `gimbal` at now_s. Call once per gimbal, then
    // mark_sent() once per tick.
    std::vector<Endpoint> due_state(const std::string& gimbal, double now_s) const;
    const Subscription* find(const Endpoint& who) const;
    Subscription* find(const Endpoint& who);
    void mark_sent(double now_s);
    // Subscribers that want events of `gimbal`.
    std::vector<Endpoint> event_targets(const std::string& gimbal) const;
    // When the next STATE datagram (or expiry) is due; nullopt when nobody subscribes.
    std::optional<double> next_due() const;

    std::size_t size() const { return subs_.size(); }
    std::size_t capacity() const { return max_; }
    std::size_t per_host_capacity() const { return max_per_host_; }

  private:
    static bool covers(const Subscription& s, const std::string& gimbal) {
        return !s.gimbal || *s.gimbal == gimbal;
    }
    std::size_t host_count(const boost::asio::ip::address& address) const;

    std::size_t max_;
    std::size_t max_per_host_;
    std::map<Endpoint, Subscription> subs_;
};

}  // namespace gimbald
