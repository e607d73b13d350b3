// The daemon's own laser safety (contract section 4.2, rules 4 and 5): a dead-man timer per
// laser index after a fire command, and cease-fire for every index last commanded to fire on
// shutdown and on reconnect. Pure: deadlines are in the caller's seconds.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "command/result.hpp"

namespace gimbal::session {

class LaserGuard {
  public:
    explicit LaserGuard(double fire_timeout_s) : timeout_s_(fire_timeout_s) {}

    // A laser command for intent.index was written at now_s: it replaces that index's state.
    void commanded(const command::LaserIntent& intent, double now_s);

    struct Cease {
        std::uint8_t index;
        std::vector<std::uint8_t> frame;
    };
    // Dead-man expiries at now_s, each reported once. The index stays "firing" until the
    // caller confirms with ceased(index) that the cease-fire was written, so one that could
    // not be written (link down) is sent again on reconnect.
    std::vector<Cease> expired(double now_s);
    // Cease-fire for every index last commanded to fire (shutdown, reconnect).
    std::vector<Cease> cease_all() const;
    void ceased(std::uint8_t index);

    std::optional<double> next_deadline() const;
    bool firing(std::uint8_t index) const;

  private:
    struct Slot {
        bool firing = false;
        bool deadline_armed = false;
        double deadline_s = 0;
        std::vector<std::uint8_t> cease_frame;
    };
    double timeout_s_;
    std::array<Slot, 2> slots_{};
};

}  // namespace gimbal::session
