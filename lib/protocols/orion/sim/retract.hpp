// A retraction mechanism: deploy and retract move the arm at a constant rate between the
// deployed (0 rad) and retracted positions; disable stops the motor where it is.
#pragma once

#include <cstdint>

#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/packets_telemetry.hpp"

namespace gimbal::sim {

class Retract {
  public:
    explicit Retract(double retracted_pos = 1.5, double rate = 0.5);

    void command(orion::RetractCmd cmd);
    void step(double dt);

    orion::RetractCmd last_command() const { return cmd_; }
    orion::RetractState state() const { return state_; }
    double position() const { return pos_; }  // rad, 0 = deployed

  private:
    double retracted_pos_;
    double rate_;  // rad/s
    orion::RetractCmd cmd_ = orion::RetractCmd::deploy;
    orion::RetractState state_ = orion::RetractState::deployed;
    double pos_ = 0;
};

}  // namespace gimbal::sim
