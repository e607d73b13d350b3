// The byte link between the daemon and one gimbal: TCP, serial or an in-process simulator.
// Links carry bytes only; framing and decoding happen above (the session feeds the bytes into
// the protocol's framer). All links run on one single-threaded io_context.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gimbald {

struct LinkStats {
    std::uint64_t rx_bytes = 0;
    std::uint64_t tx_bytes = 0;
    std::uint64_t tx_packets = 0;  // packets written completely
    std::uint64_t tx_dropped = 0;  // packets refused by send() or discarded on a disconnect
    std::uint64_t reconnects = 0;  // successful connects after the first one
    std::optional<std::chrono::steady_clock::time_point> last_rx;
};

// Bounds of the outgoing packet queue: send() refuses a packet that would exceed either.
struct SendQueueLimits {
    std::size_t max_packets = 256;
    std::size_t max_bytes = 64 * 1024;
};

class Link {
  public:
    using DataHandler = std::function<void(std::span<const std::uint8_t>)>;
    // Called on every connect (true) and every disconnect (false); not called by stop().
    using StateHandler = std::function<void(bool connected)>;
    // For logs (event link_error): `what` is a short slug ("connect", "read", "silence", ...),
    // `detail` a human readable explanation including what happens next.
    using ErrorHandler = std::function<void(std::string_view what, std::string_view detail)>;

    virtual ~Link() = default;

    // Begins connecting (and reconnecting forever). Calling start() again restarts the link.
    virtual void start(DataHandler, StateHandler, ErrorHandler) = 0;
    // Closes the link and cancels its timers; no handler is called after stop() returns.
    virtual void stop() = 0;
    virtual bool connected() const = 0;
    // Queues ONE whole packet. Returns false and queues nothing when not connected or when the
    // bounded queue is full. Packets are written in order, never interleaved; a write error
    // counts as a disconnect. Queued packets are discarded (counted in tx_dropped) on a
    // disconnect: stale commands must not reach the gimbal after a reconnect.
    virtual bool send(std::vector<std::uint8_t> packet) = 0;
    // Synchronous best-effort flush on shutdown: writes whatever is queued plus `packet` now
    // (blocking, short timeout). Used to send the laser cease-fire on SIGTERM.
    virtual void send_now(std::span<const std::uint8_t> packet) = 0;
    virtual const LinkStats& stats() const = 0;
    virtual std::string type() const = 0;      // "tcp", "serial", "sim"
    virtual std::string endpoint() const = 0;  // "127.0.0.1:8747", "/dev/ttyUSB0@115200", "sim"
};

}  // namespace gimbald
