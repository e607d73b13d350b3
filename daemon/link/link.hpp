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
    std::uint64_t tx_packets = 0;    // packets written completely
    std::uint64_t tx_dropped = 0;    // packets refused by send(), discarded on a disconnect, or
                                     // displaced by safety traffic
    std::uint64_t tx_displaced = 0;  // of those: queued packets dropped to make room for a
                                     // cease-fire (contract section 14)
    std::uint64_t reconnects = 0;    // successful connects after the first one
    std::optional<std::chrono::steady_clock::time_point> last_rx;
};

// Bounds of the outgoing packet queue: send() refuses a packet that would exceed either;
// send_safety() makes room instead (link/send_queue.hpp).
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
    // A safety packet's fate: true once its last byte was written, false when it was
    // discarded (the link went down first). Called from the io_context, never from inside a
    // Link method, and not after stop().
    using WrittenHandler = std::function<void(bool written)>;

    virtual ~Link() = default;

    // Begins connecting (and reconnecting forever). Calling start() again restarts the link.
    virtual void start(DataHandler, StateHandler, ErrorHandler) = 0;
    // Closes the link and cancels its timers; no handler is called after stop() returns.
    virtual void stop() = 0;
    virtual bool connected() const = 0;
    // Queues ONE whole packet. Returns false and queues nothing when not connected or when the
    // bounded queue is full. Packets are written in order, never interleaved (an idle link
    // writes at once; the handlers are never called from inside a send); a write error
    // counts as a disconnect. Queued packets are discarded (counted in tx_dropped) on a
    // disconnect: stale commands must not reach the gimbal after a reconnect.
    // A queued packet may be displaced (dropped, counted) to make room for safety traffic.
    virtual bool send(std::vector<std::uint8_t> packet) = 0;
    // Like send() - same order, same bounds - but never displaced: laser commands, whose loss
    // would leave the daemon's record of the laser wrong.
    virtual bool send_kept(std::vector<std::uint8_t> packet) = 0;
    // A laser cease-fire (contract section 14): written before everything queued (after a
    // packet already half written), never refused for a full queue - queued send() traffic is
    // displaced instead. Returns false, and never calls `on_written`, when not connected;
    // otherwise `on_written` is called exactly once (unless the link is stopped first).
    virtual bool send_safety(std::vector<std::uint8_t> packet, WrittenHandler on_written) = 0;
    // Synchronous best-effort flush on shutdown: finishes a half-written packet, writes
    // `packet`, then whatever else is queued (blocking, short timeout). Used to send the laser
    // cease-fire on SIGTERM. True when `packet` was written completely.
    virtual bool send_now(std::span<const std::uint8_t> packet) = 0;
    virtual const LinkStats& stats() const = 0;
    virtual std::string type() const = 0;      // "tcp", "serial", "sim"
    virtual std::string endpoint() const = 0;  // "127.0.0.1:8747", "/dev/ttyUSB0@115200", "sim"
};

}  // namespace gimbald
