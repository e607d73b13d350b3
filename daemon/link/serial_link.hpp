// Serial link (real UART, USB adapter or pseudo-terminal): raw 8N1 at `baud`, no flow control.
// A device missing at start, or disappearing later (USB unplug, pty closed), is retried with
// the backoff, never fatal.
//
// The port is a posix::stream_descriptor configured with termios rather than an
// asio::serial_port: serial_port has no async_wait(wait_write) and no non_blocking(), which
// the shared writer needs to know exactly how much of a packet went out (see stream_link.hpp).
// Underneath, Asio's serial_port is the same reactive descriptor with the same termios calls.
#pragma once

#include <termios.h>

#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>

#include "link/backoff.hpp"
#include "link/link_config.hpp"
#include "link/stream_link.hpp"

namespace gimbald {

// The `link` section of type "serial" (link_config.hpp: the device, re-resolved on every
// attempt so symlinks are welcome; baud; reconnect delays) and what the daemon adds.
struct SerialLinkOptions : gimbal::daemon::SerialLink {
    SerialLinkOptions() { baud = 115200; }
    explicit SerialLinkOptions(gimbal::daemon::SerialLink config) : SerialLink(std::move(config)) {}
    double silence_timeout_s = 0.0;  // 0: off (a quiet serial gimbal is not necessarily dead)
    SendQueueLimits queue;
    double send_now_timeout_s = 0.25;
};

// The termios speed constant for a baud rate, if the platform has one.
std::optional<speed_t> baud_to_speed(unsigned baud);

class SerialLink final : public StreamLink<boost::asio::posix::stream_descriptor> {
  public:
    // Throws std::invalid_argument for a baud rate termios does not know (a startup error).
    SerialLink(boost::asio::io_context& io, SerialLinkOptions options);
    SerialLink(boost::asio::io_context& io, SerialLinkOptions options, Backoff backoff);

    std::string type() const override { return "serial"; }
    std::string endpoint() const override;  // "/dev/ttyUSB0@115200"

  private:
    void open() override;

    SerialLinkOptions options_;
    speed_t speed_;
};

}  // namespace gimbald
