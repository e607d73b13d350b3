#include "session/laser_guard.hpp"

namespace gimbal::session {

void LaserGuard::commanded(const command::LaserIntent& intent, double now_s) {
    if (intent.index >= slots_.size()) return;
    auto& slot = slots_[intent.index];
    slot.firing = intent.fire;
    slot.deadline_armed = intent.fire;
    slot.deadline_s = now_s + timeout_s_;
    slot.cease_frame = intent.cease_frame;
    slot.serial = ++next_serial_;
    slot.queued_s.reset();
    slot.overdue_reported = false;
}

std::vector<LaserGuard::Cease> LaserGuard::expired(double now_s) {
    std::vector<Cease> out;
    for (std::uint8_t i = 0; i < slots_.size(); ++i) {
        auto& slot = slots_[i];
        if (slot.firing && slot.deadline_armed && slot.deadline_s <= now_s) {
            slot.deadline_armed = false;
            out.push_back(Cease{i, slot.cease_frame, slot.serial});
        }
    }
    return out;
}

std::vector<LaserGuard::Cease> LaserGuard::cease_all() const {
    std::vector<Cease> out;
    for (std::uint8_t i = 0; i < slots_.size(); ++i)
        if (slots_[i].firing) out.push_back(Cease{i, slots_[i].cease_frame, slots_[i].serial});
    return out;
}

LaserGuard::Slot* LaserGuard::current(const Cease& cease) {
    if (cease.index >= slots_.size()) return nullptr;
    Slot& slot = slots_[cease.index];
    return slot.serial == cease.serial ? &slot : nullptr;
}

void LaserGuard::cease_queued(const Cease& cease, double now_s) {
    if (Slot* slot = current(cease)) {
        slot->queued_s = now_s;
        slot->overdue_reported = false;
    }
}

bool LaserGuard::ceased(const Cease& cease) {
    Slot* slot = current(cease);
    if (!slot) return false;
    slot->firing = false;
    slot->deadline_armed = false;
    slot->queued_s.reset();
    return true;
}

void LaserGuard::cease_discarded(const Cease& cease) {
    if (Slot* slot = current(cease)) slot->queued_s.reset();
}

void LaserGuard::ceased(std::uint8_t index) {
    if (index < slots_.size()) {
        slots_[index].firing = false;
        slots_[index].deadline_armed = false;
        slots_[index].queued_s.reset();
    }
}

std::vector<std::uint8_t> LaserGuard::overdue(double now_s, double after_s) {
    std::vector<std::uint8_t> out;
    for (std::uint8_t i = 0; i < slots_.size(); ++i) {
        auto& slot = slots_[i];
        if (slot.firing && slot.queued_s && !slot.overdue_reported &&
            now_s - *slot.queued_s > after_s) {
            slot.overdue_reported = true;
            out.push_back(i);
        }
    }
    return out;
}

std::optional<double> LaserGuard::next_deadline() const {
    std::optional<double> next;
    for (const auto& slot : slots_)
        if (slot.firing && slot.deadline_armed && (!next || slot.deadline_s < *next))
            next = slot.deadline_s;
    return next;
}

bool LaserGuard::firing(std::uint8_t index) const {
    return index < slots_.size() && slots_[index].firing;
}

}  // namespace gimbal::session
