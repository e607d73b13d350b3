#include "state_pacer.hpp"

namespace gimbald::mqtt {

namespace {

std::chrono::steady_clock::duration periods(double n, double rate_hz) {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(n / rate_hz));
}

}  // namespace

StatePacer::StatePacer(boost::asio::io_context& io, double rate_hz, std::function<void()> publish)
    : timer_(io),
      min_interval_(periods(0.8, rate_hz)),
      repeat_interval_(periods(1.25, rate_hz)),
      publish_(std::move(publish)) {}

void StatePacer::on_telemetry() {
    if (stopped_ || deferred_) return;  // already due: the pending STATE will carry it
    const auto age = std::chrono::steady_clock::now() - last_publish_;
    if (age >= min_interval_) {
        publish_now();
        return;
    }
    deferred_ = true;
    arm(min_interval_ - age);
}

void StatePacer::publish_now() {
    if (stopped_) return;
    deferred_ = false;
    last_publish_ = std::chrono::steady_clock::now();
    publish_();
    arm(repeat_interval_);
}

void StatePacer::stop() {
    stopped_ = true;
    timer_.cancel();
}

void StatePacer::arm(std::chrono::steady_clock::duration after) {
    // Re-arming cancels the previous wait; its handler sees operation_aborted.
    timer_.expires_after(after);
    timer_.async_wait([this, generation = ++generation_](const boost::system::error_code& ec) {
        if (!ec && generation == generation_) publish_now();
    });
}

}  // namespace gimbald::mqtt
