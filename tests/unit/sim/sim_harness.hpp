// Drives a simulated gimbal through its Device interface, as the daemon does: bytes in, bytes
// out, time passed in. Not a test file itself (only test_*.cpp are compiled).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/sim/orion_sim.hpp"

namespace sim_test {

using Bytes = std::vector<std::uint8_t>;

class Harness {
  public:
    explicit Harness(const gimbal::sim::OrionSimOptions& options = {})
        : device_(gimbal::sim::make_orion_sim(options)) {}

    // Advances `seconds` of simulated time (run(0) just starts the device) in `step` increments;
    // returns the frames sent.
    std::vector<gimbal::orion::Frame> run(double seconds, double step = 0.02) {
        std::vector<gimbal::orion::Frame> frames;
        const double end = now_ + seconds;
        do {
            now_ = std::min(end, now_ + step);
            Bytes out;
            device_->advance(now_, out);
            raw_.insert(raw_.end(), out.begin(), out.end());
            framer_.push(out, [&](const gimbal::orion::Frame& f) { frames.push_back(f); });
        } while (now_ < end);
        return frames;
    }

    void send(const Bytes& bytes) { device_->receive(bytes, now_); }
    template <class P>
    void send_packet(const P& packet) {
        send(gimbal::orion::to_wire(packet));
    }
    void request(std::uint8_t id) { send(gimbal::orion::request_bytes(id)); }

    double now() const { return now_; }
    const gimbal::sim::Device& device() const { return *device_; }
    // Every byte the device sent so far.
    const Bytes& raw() const { return raw_; }
    const gimbal::orion::FramerStats& framer_stats() const { return framer_.stats(); }

  private:
    std::unique_ptr<gimbal::sim::Device> device_;
    gimbal::orion::Framer framer_;
    double now_ = 5000.0;  // any epoch: the device counts from its first call
    Bytes raw_;
};

template <class P>
std::vector<P> decoded(const std::vector<gimbal::orion::Frame>& frames) {
    std::vector<P> out;
    for (const auto& f : frames)
        if (f.id == P::id)
            if (auto d = gimbal::orion::decode<P>(f.data())) out.push_back(d.value);
    return out;
}

inline std::size_t count_id(const std::vector<gimbal::orion::Frame>& frames, std::uint8_t id) {
    std::size_t n = 0;
    for (const auto& f : frames) n += f.id == id ? 1 : 0;
    return n;
}

}  // namespace sim_test
