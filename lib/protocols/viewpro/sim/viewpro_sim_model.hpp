// The simulated Viewpro behind make_viewpro_sim(). Private to lib/sim: everyone else talks to
// it as a Device, in bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "protocols/viewpro/codec/input_framer.hpp"
#include "protocols/viewpro/codec/output.hpp"
#include "protocols/viewpro/sim/viewpro_sim.hpp"
#include "protocols/viewpro/sim/viewpro_sim_target.hpp"
#include "sim/device.hpp"

namespace gimbal::sim {

class ViewproSim final : public Device {
  public:
    explicit ViewproSim(const ViewproSimOptions& options);

    void receive(std::span<const std::uint8_t> bytes, double now_s) override;
    void advance(double now_s, std::vector<std::uint8_t>& out) override;

  private:
    void run_until(double now_s);
    void handle(const viewpro::InputFrame& frame);
    void set_clock(const viewpro::DateTime& utc);
    // What the gimbal measures and works out at model time t_, in the selected format.
    viewpro::Output measure();
    double gimbal_yaw_deg() const;
    double noise();

    ViewproSimOptions options_;

    // time
    bool started_ = false;
    double t0_ = 0;                // caller's clock at the model's start
    double t_ = 0;                 // model time, seconds since the start
    std::uint64_t next_tick_ = 0;  // output tick k is due at k * output_period_s
    double utc_at_t_base_s_ = 0;   // UTC (Unix seconds) at model time t_base_s_
    double t_base_s_ = 0;

    // inputs
    viewpro::InputFramer framer_;
    std::uint8_t mode_byte_;
    int yaw_shift_hundredths_ = 0;
    int pitch_shift_hundredths_ = 0;
    ViewproPose pose_;
    std::optional<double> laser_range_m_;  // from IN3, until an IN1/IN2 replaces it

    // output
    std::vector<std::uint8_t> pending_;
    std::mt19937 rng_;
};

}  // namespace gimbal::sim
