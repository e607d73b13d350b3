// Invalidates pending Asio handlers. Every handler is wrapped with wrap(); after reset() (or
// the owner's destruction) a wrapped handler still queued in the io_context does nothing, so
// a closed connection's late completions (operation_aborted and friends) can neither touch a
// new connection nor a destroyed object. This is how stop() guarantees silence.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>

namespace gimbald {

class Lifetime {
  public:
    template <class F>
    auto wrap(F f) const {
        return
            [alive = std::weak_ptr<const char>(token_), f = std::move(f)](auto&&... args) mutable {
                if (!alive.expired()) f(std::forward<decltype(args)>(args)...);
            };
    }

    // Orphans every handler wrapped so far.
    void reset() {
        token_ = std::make_shared<const char>('\0');
        ++generation_;
    }

    // Changes on every reset(): compare before and after calling user code that may stop us.
    std::uint64_t generation() const { return generation_; }

  private:
    std::shared_ptr<const char> token_ = std::make_shared<const char>('\0');
    std::uint64_t generation_ = 0;
};

}  // namespace gimbald
