// When one gimbal's STATE goes to the broker. New telemetry goes out at once (telemetry
// received -> subscriber in milliseconds, not up to a period later) unless the previous STATE
// is younger than 0.8 of the period; then it goes as soon as it is that old, so the rate
// stays state_rate_hz. While no telemetry arrives (link down, stale, a gimbal slower than
// the rate) STATE is repeated every 1.25 periods: a fixed tick would race the telemetry and
// publish just before it arrives, holding the new values back a whole period.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>

namespace gimbald::mqtt {

class StatePacer {
  public:
    StatePacer(boost::asio::io_context& io, double rate_hz, std::function<void()> publish);

    // New telemetry arrived.
    void on_telemetry();
    // Publishes now (a (re)connection, the first STATE) and restarts the pacing.
    void publish_now();
    void stop();

  private:
    void arm(std::chrono::steady_clock::duration after);

    boost::asio::steady_timer timer_;
    std::chrono::steady_clock::duration min_interval_;
    std::chrono::steady_clock::duration repeat_interval_;
    std::function<void()> publish_;
    std::chrono::steady_clock::time_point last_publish_{};
    bool deferred_ = false;  // the timer holds back new telemetry, not a repeat
    bool stopped_ = false;
    // A wait that expired just as it was re-armed still runs its handler: only the latest
    // one publishes.
    unsigned generation_ = 0;
};

}  // namespace gimbald::mqtt
