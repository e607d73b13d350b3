// The daemon's own laser safety (contract section 4.2, rules 4 and 5, and section 14): a
// dead-man timer per laser index after a fire command, and cease-fire for every index last
// commanded to fire on shutdown and on reconnect. An index stays "firing" until the caller
// confirms that its cease-fire was written. Pure: times are in the caller's seconds.
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
        // Which command of the index it answers: a cease confirmed after a newer command for
        // the same index (written behind it) must not mark that newer fire as ceased.
        std::uint64_t serial = 0;
    };
    // Dead-man expiries at now_s, each reported once. The index stays "firing" until the
    // caller confirms with ceased() that the cease-fire was written, so one that could not
    // be written (link down) is sent again on reconnect.
    std::vector<Cease> expired(double now_s);
    // Cease-fire for every index last commanded to fire (shutdown, reconnect).
    std::vector<Cease> cease_all() const;

    // The cease-fire was handed to the link at now_s and waits to be written.
    void cease_queued(const Cease& cease, double now_s);
    // It was written: the index stops firing unless a newer command came since. Returns
    // whether it applied.
    bool ceased(const Cease& cease);
    // It was discarded (the link went down): the index still fires, for the reconnect.
    void cease_discarded(const Cease& cease);
    // Unconditionally not firing (a cease-fire written synchronously on shutdown).
    void ceased(std::uint8_t index);
    // Indexes whose queued cease-fire has waited longer than after_s: each reported once.
    std::vector<std::uint8_t> overdue(double now_s, double after_s);

    std::optional<double> next_deadline() const;
    bool firing(std::uint8_t index) const;

  private:
    struct Slot {
        bool firing = false;
        bool deadline_armed = false;
        double deadline_s = 0;
        std::vector<std::uint8_t> cease_frame;
        std::uint64_t serial = 0;
        std::optional<double> queued_s;  // a cease-fire waits to be written since then
        bool overdue_reported = false;
    };
    Slot* current(const Cease& cease);

    double timeout_s_;
    std::uint64_t next_serial_ = 0;
    std::array<Slot, 2> slots_{};
};

}  // namespace gimbal::session
