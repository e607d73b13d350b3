#include "link/serial_link.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace gimbald {

namespace {

StreamLinkOptions stream_options(const SerialLinkOptions& o) {
    return {.silence_timeout_s = o.silence_timeout_s,
            .queue = o.queue,
            .send_now_timeout_s = o.send_now_timeout_s};
}

Backoff backoff_from(const SerialLinkOptions& o) {
    return Backoff(BackoffOptions{.min_s = o.reconnect_min_s, .max_s = o.reconnect_max_s});
}

speed_t checked_speed(unsigned baud) {
    const std::optional<speed_t> speed = baud_to_speed(baud);
    if (!speed) throw std::invalid_argument("unsupported baud rate " + std::to_string(baud));
    return *speed;
}

std::string errno_text(int error) {
    return std::strerror(error);
}

// Raw 8N1, no flow control, reads return as soon as one byte is there. Returns "" or an error.
std::string configure_raw(int fd, speed_t speed) {
    termios tio{};
    if (::tcgetattr(fd, &tio) != 0) return "tcgetattr: " + errno_text(errno);
    // cfmakeraw: no echo, no canonical mode, no CR/LF translation, no signals, 8 bits.
    ::cfmakeraw(&tio);
    tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
    tio.c_cflag |= CS8 | CLOCAL | CREAD;
    tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    if (::cfsetispeed(&tio, speed) != 0 || ::cfsetospeed(&tio, speed) != 0) {
        return "cfsetspeed: " + errno_text(errno);
    }
    if (::tcsetattr(fd, TCSANOW, &tio) != 0) return "tcsetattr: " + errno_text(errno);
    ::tcflush(fd, TCIOFLUSH);  // stale bytes from before we opened the port
    return {};
}

}  // namespace

std::optional<speed_t> baud_to_speed(unsigned baud) {
    switch (baud) {
        case 1200:
            return B1200;
        case 2400:
            return B2400;
        case 4800:
            return B4800;
        case 9600:
            return B9600;
        case 19200:
            return B19200;
        case 38400:
            return B38400;
        case 57600:
            return B57600;
        case 115200:
            return B115200;
        case 230400:
            return B230400;
        case 460800:
            return B460800;
        case 500000:
            return B500000;
        case 576000:
            return B576000;
        case 921600:
            return B921600;
        case 1000000:
            return B1000000;
        case 1500000:
            return B1500000;
        case 2000000:
            return B2000000;
        case 3000000:
            return B3000000;
        case 4000000:
            return B4000000;
        default:
            return std::nullopt;
    }
}

SerialLink::SerialLink(boost::asio::io_context& io, SerialLinkOptions options)
    : SerialLink(io, options, backoff_from(options)) {}

SerialLink::SerialLink(boost::asio::io_context& io, SerialLinkOptions options, Backoff backoff)
    : StreamLink(io, stream_options(options), std::move(backoff)),
      options_(std::move(options)),
      speed_(checked_speed(options_.baud)) {}

std::string SerialLink::endpoint() const {
    return options_.device + "@" + std::to_string(options_.baud);
}

void SerialLink::open() {
    const int fd = ::open(options_.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return attempt_failed("open", options_.device + ": " + errno_text(errno));
    if (const std::string error = configure_raw(fd, speed_); !error.empty()) {
        ::close(fd);
        return attempt_failed("configure", options_.device + ": " + error);
    }
    stream().emplace(io(), fd);
    established();
}

}  // namespace gimbald
