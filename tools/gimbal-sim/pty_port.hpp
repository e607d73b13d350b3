// A pseudo-terminal the controller opens like a serial port. The simulator keeps the master
// side; it notices when the other side has the device open (a read on the master fails with
// EIO while nobody has) and only then sends, so a controller that opens the device late does
// not first read minutes of stale bytes. Closing and reopening the device is fine.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "byte_port.hpp"

namespace gimbal_sim {

class PtyPort {
  public:
    using StateHandler = std::function<void(bool open)>;

    // Opens the pty (raw, 8 bits) and makes `link` point at it when not empty; throws on
    // failure (startup error).
    PtyPort(boost::asio::io_context& io, std::string link, BytesHandler on_bytes,
            StateHandler on_state);
    ~PtyPort();
    PtyPort(const PtyPort&) = delete;
    PtyPort& operator=(const PtyPort&) = delete;

    const std::string& device() const { return device_; }
    void start();
    void stop();

    bool peer_open() const { return peer_open_; }
    // Reads only what the policy allows (fault injection); without one, as fast as it comes.
    void set_read_policy(ReadPolicy policy) { read_policy_ = std::move(policy); }
    // Writes what the pty takes now; the rest (and everything while nobody has the device
    // open) is dropped, as on a serial line nobody listens to.
    void write(std::span<const std::uint8_t> bytes);
    std::uint64_t dropped_bytes() const { return dropped_bytes_; }

  private:
    void poll();       // while nobody has the device open: look again every 100 ms
    void wait_read();  // while someone has: wait for bytes
    // Reads what is there (and the read policy allows).
    enum class ReadResult { drained, throttled, closed };
    ReadResult read_available();
    void set_peer_open(bool open);

    boost::asio::posix::stream_descriptor master_;
    boost::asio::steady_timer poll_timer_;
    std::string device_;
    std::string link_;
    BytesHandler on_bytes_;
    StateHandler on_state_;
    ReadPolicy read_policy_;
    double retry_after_s_ = 0;  // with ReadResult::throttled
    std::vector<std::uint8_t> buffer_ = std::vector<std::uint8_t>(4096);
    bool peer_open_ = false;
    bool stopped_ = false;
    std::uint64_t dropped_bytes_ = 0;
};

}  // namespace gimbal_sim
