#include "link/send_queue.hpp"

#include <utility>

namespace gimbald {

bool SendQueue::fits(std::size_t size) const {
    return packets() < limits_.max_packets && bytes_ + size <= limits_.max_bytes;
}

bool SendQueue::push(Bytes packet, Kind kind) {
    if (!fits(packet.size())) return false;
    if (packet.empty()) return true;
    bytes_ += packet.size();
    normal_.push_back(Normal{std::move(packet), kind});
    return true;
}

bool SendQueue::displace_one() {
    // The front normal packet is off limits while its first bytes are on the wire.
    const std::size_t first = offset_ > 0 && !offset_in_safety_ ? 1 : 0;
    for (std::size_t i = first; i < normal_.size(); ++i) {
        if (normal_[i].kind == Kind::kept) continue;  // none left after push_safety's move
        bytes_ -= normal_[i].bytes.size();
        normal_.erase(normal_.begin() + static_cast<std::ptrdiff_t>(i));
        ++displaced_;
        return true;
    }
    return false;
}

std::size_t SendQueue::push_safety(Bytes packet, Link::WrittenHandler on_written) {
    const std::uint64_t before = displaced_;
    // Laser commands not yet started go first, in order: the cease must follow the fire.
    const std::size_t first = offset_ > 0 && !offset_in_safety_ ? 1 : 0;
    for (std::size_t i = first; i < normal_.size();) {
        if (normal_[i].kind != Kind::kept) {
            ++i;
            continue;
        }
        safety_.push_back(Safety{std::move(normal_[i].bytes), nullptr});
        normal_.erase(normal_.begin() + static_cast<std::ptrdiff_t>(i));
    }
    // Room is made while there is something to give up; past that the packet goes in anyway
    // (a cease-fire is a few bytes, and at most one per laser is ever pending).
    while (!fits(packet.size()) && displace_one()) {
    }
    bytes_ += packet.size();
    safety_.push_back(Safety{std::move(packet), std::move(on_written)});
    return static_cast<std::size_t>(displaced_ - before);
}

bool SendQueue::current_is_safety() const {
    if (offset_ > 0) return offset_in_safety_;
    return !safety_.empty();
}

std::span<const std::uint8_t> SendQueue::next() const {
    if (empty()) return {};
    const Bytes& bytes = current_is_safety() ? safety_.front().bytes : normal_.front().bytes;
    return std::span<const std::uint8_t>(bytes).subspan(offset_);
}

SendQueue::Written SendQueue::written(std::size_t n) {
    Written out;
    if (empty() || n == 0) return out;
    const bool safety = current_is_safety();
    const std::size_t size = safety ? safety_.front().bytes.size() : normal_.front().bytes.size();
    offset_in_safety_ = safety;
    offset_ += n;
    if (offset_ < size) return out;
    out.packet_done = true;
    bytes_ -= size;
    offset_ = 0;
    if (safety) {
        out.safety = true;
        out.safety_done = std::move(safety_.front().on_written);
        safety_.pop_front();
    } else {
        normal_.pop_front();
    }
    return out;
}

std::vector<Link::WrittenHandler> SendQueue::clear() {
    std::vector<Link::WrittenHandler> handlers;
    for (auto& s : safety_)
        if (s.on_written) handlers.push_back(std::move(s.on_written));
    dropped_ += packets();
    safety_.clear();
    normal_.clear();
    bytes_ = 0;
    offset_ = 0;
    return handlers;
}

}  // namespace gimbald
