#include "auth/nonce_window.hpp"

namespace gimbal::auth {

NonceWindow::Result NonceWindow::remember(const std::string& nonce, std::int64_t forget_at_ms,
                                          std::int64_t now_ms) {
    while (!by_expiry_.empty() && by_expiry_.begin()->first <= now_ms) {
        by_nonce_.erase(by_expiry_.begin()->second);
        by_expiry_.erase(by_expiry_.begin());
    }
    if (by_nonce_.contains(nonce)) return Result::replayed;
    if (by_nonce_.size() >= capacity_) return Result::full;
    by_nonce_.emplace(nonce, forget_at_ms);
    by_expiry_.emplace(forget_at_ms, nonce);
    return Result::fresh;
}

}  // namespace gimbal::auth
