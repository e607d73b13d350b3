#include "seqpacket.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace gimbal_track {

namespace {

std::string system_error(const char* what) {
    return std::string(what) + ": " + std::strerror(errno);
}

}  // namespace

SeqPacket SeqPacket::adopt(int fd) {
    int type = 0;
    socklen_t length = sizeof(type);
    if (::getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &length) != 0)
        return SeqPacket(
            -1, "--fd " + std::to_string(fd) + " is not a socket: " + std::strerror(errno));
    if (type != SOCK_SEQPACKET)
        return SeqPacket(-1, "--fd " + std::to_string(fd) + " is not a SOCK_SEQPACKET socket");
    return SeqPacket(fd);
}

SeqPacket SeqPacket::connect(const std::string& path) {
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    if (path.empty() || path.size() >= sizeof(address.sun_path))
        return SeqPacket(-1, "--socket: a path of 1 to " +
                                 std::to_string(sizeof(address.sun_path) - 1) + " bytes");
    std::memcpy(address.sun_path, path.data(), path.size());
    const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
    if (fd < 0) return SeqPacket(-1, system_error("socket"));
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
        const std::string error = "connecting to " + path + ": " + std::strerror(errno);
        ::close(fd);
        return SeqPacket(-1, error);
    }
    return SeqPacket(fd);
}

SeqPacket::SeqPacket(SeqPacket&& other) noexcept : fd_(other.fd_), error_(std::move(other.error_)) {
    other.fd_ = -1;
}

SeqPacket::~SeqPacket() {
    if (fd_ >= 0) ::close(fd_);
}

SeqPacket::Received SeqPacket::receive(std::vector<std::uint8_t>& buffer, std::size_t limit) {
    buffer.resize(limit + 1);  // one byte more: a datagram that fills it is too large
    iovec io{buffer.data(), buffer.size()};
    msghdr message{};
    message.msg_iov = &io;
    message.msg_iovlen = 1;
    const ssize_t n = ::recvmsg(fd_, &message, MSG_CMSG_CLOEXEC);
    if (n < 0) {
        if (errno == EINTR) return Received::interrupted;
        error_ = system_error("recvmsg");
        return Received::failed;
    }
    if (n == 0) return Received::closed;
    if ((message.msg_flags & MSG_TRUNC) != 0 || static_cast<std::size_t>(n) > limit) {
        buffer.clear();
        return Received::too_large;
    }
    buffer.resize(static_cast<std::size_t>(n));
    return Received::message;
}

bool SeqPacket::pending(int wait_ms) const {
    pollfd p{fd_, POLLIN, 0};
    return ::poll(&p, 1, wait_ms) == 1 && (p.revents & POLLIN) != 0;
}

bool SeqPacket::send(std::span<const std::uint8_t> datagram) {
    for (;;) {
        const ssize_t n = ::send(fd_, datagram.data(), datagram.size(), MSG_NOSIGNAL);
        if (n >= 0) return true;
        if (errno == EINTR) continue;
        error_ = system_error("send");
        return false;
    }
}

}  // namespace gimbal_track
