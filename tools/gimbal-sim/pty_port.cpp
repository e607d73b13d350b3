#include "pty_port.hpp"

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace gimbal_sim {

namespace asio = boost::asio;

namespace {

[[noreturn]] void fail(const std::string& what) {
    throw std::system_error(errno, std::generic_category(), what);
}

}  // namespace

PtyPort::PtyPort(asio::io_context& io, std::string link, BytesHandler on_bytes,
                 StateHandler on_state)
    : master_(io),
      poll_timer_(io),
      link_(std::move(link)),
      on_bytes_(std::move(on_bytes)),
      on_state_(std::move(on_state)) {
    int master = -1;
    int slave = -1;
    char name[256] = {};
    if (::openpty(&master, &slave, name, nullptr, nullptr) != 0) fail("openpty");
    device_ = name;
    termios tio{};
    if (::tcgetattr(slave, &tio) == 0) {
        ::cfmakeraw(&tio);
        ::cfsetspeed(&tio, B115200);
        ::tcsetattr(slave, TCSANOW, &tio);
    }
    // Our copy of the slave goes: from now on a read on the master tells whether anyone
    // else has the device open.
    ::close(slave);
    const int flags = ::fcntl(master, F_GETFL);
    ::fcntl(master, F_SETFL, flags | O_NONBLOCK);
    master_.assign(master);

    if (!link_.empty()) {
        std::error_code ec;
        if (std::filesystem::is_symlink(std::filesystem::symlink_status(link_, ec)))
            std::filesystem::remove(link_, ec);
        std::filesystem::create_symlink(device_, link_, ec);
        if (ec) throw std::system_error(ec, "symlink " + link_);
    }
}

PtyPort::~PtyPort() {
    if (!link_.empty()) {
        std::error_code ec;
        if (std::filesystem::read_symlink(link_, ec) == device_) std::filesystem::remove(link_, ec);
    }
}

void PtyPort::start() {
    poll();
}

void PtyPort::stop() {
    stopped_ = true;
    poll_timer_.cancel();
    boost::system::error_code ignored;
    master_.cancel(ignored);
    master_.close(ignored);
}

void PtyPort::set_peer_open(bool open) {
    if (open == peer_open_) return;
    peer_open_ = open;
    if (on_state_) on_state_(open);
}

PtyPort::ReadResult PtyPort::read_available() {
    while (true) {
        std::size_t limit = buffer_.size();
        if (read_policy_) {
            const ReadBudget budget = read_policy_();
            if (budget.bytes == 0) {  // not now: the pty's buffer fills meanwhile
                retry_after_s_ = budget.retry_after_s;
                return ReadResult::throttled;
            }
            limit = std::min(limit, budget.bytes);
        }
        const ssize_t n = ::read(master_.native_handle(), buffer_.data(), limit);
        if (n > 0) {
            set_peer_open(true);
            if (on_bytes_) on_bytes_({buffer_.data(), static_cast<std::size_t>(n)});
            if (stopped_) return ReadResult::closed;
            continue;
        }
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            set_peer_open(true);
            return ReadResult::drained;
        }
        if (n < 0 && errno == EINTR) continue;
        set_peer_open(false);  // EIO: nobody has the device open
        return ReadResult::closed;
    }
}

void PtyPort::poll() {
    if (stopped_) return;
    std::chrono::nanoseconds wait = std::chrono::milliseconds(100);
    switch (read_available()) {
        case ReadResult::drained:
            wait_read();
            return;
        case ReadResult::throttled:
            wait = std::chrono::duration_cast<std::chrono::nanoseconds>(
                std::chrono::duration<double>(retry_after_s_));
            break;
        case ReadResult::closed:
            break;
    }
    poll_timer_.expires_after(wait);
    poll_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) poll();
    });
}

void PtyPort::wait_read() {
    master_.async_wait(asio::posix::stream_descriptor::wait_read,
                       [this](const boost::system::error_code& ec) {
                           if (ec || stopped_) return;
                           poll();  // reads, or notices the close and goes back to polling
                       });
}

void PtyPort::write(std::span<const std::uint8_t> bytes) {
    if (bytes.empty()) return;
    if (!peer_open_ || stopped_) {
        dropped_bytes_ += bytes.size();
        return;
    }
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n =
            ::write(master_.native_handle(), bytes.data() + done, bytes.size() - done);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        break;  // full (EAGAIN) or closed (EIO): drop the rest
    }
    dropped_bytes_ += bytes.size() - done;
}

}  // namespace gimbal_sim
