#include "protocols/orion/sim/retract.hpp"

#include <algorithm>

namespace gimbal::sim {

Retract::Retract(double retracted_pos, double rate) : retracted_pos_(retracted_pos), rate_(rate) {}

void Retract::command(orion::RetractCmd cmd) {
    cmd_ = cmd;
    switch (cmd) {
        case orion::RetractCmd::deploy:
            state_ = pos_ <= 0 ? orion::RetractState::deployed : orion::RetractState::deploying;
            break;
        case orion::RetractCmd::retract:
            state_ = pos_ >= retracted_pos_ ? orion::RetractState::retracted
                                            : orion::RetractState::retracting;
            break;
        case orion::RetractCmd::disable:
            state_ = orion::RetractState::disabled;
            break;
        default:  // a value the ICD does not define: the mechanism faults
            state_ = orion::RetractState::fault;
            break;
    }
}

void Retract::step(double dt) {
    if (dt <= 0) return;
    if (state_ == orion::RetractState::deploying) {
        pos_ = std::max(0.0, pos_ - rate_ * dt);
        if (pos_ <= 0) state_ = orion::RetractState::deployed;
    } else if (state_ == orion::RetractState::retracting) {
        pos_ = std::min(retracted_pos_, pos_ + rate_ * dt);
        if (pos_ >= retracted_pos_) state_ = orion::RetractState::retracted;
    }
}

}  // namespace gimbal::sim
