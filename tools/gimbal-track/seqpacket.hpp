// The local socket to gimbald: SOCK_SEQPACKET, one message per datagram. gimbald hands its
// end of a socketpair over as a file descriptor; by hand and in tests gimbal-track connects
// to a listening Unix socket. It never listens and never touches the network.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace gimbal_track {

class SeqPacket {
  public:
    // Takes `fd` (checked to be a SOCK_SEQPACKET socket). On failure error() says why.
    static SeqPacket adopt(int fd);
    // Connects to the Unix socket at `path`.
    static SeqPacket connect(const std::string& path);
    SeqPacket(SeqPacket&& other) noexcept;
    SeqPacket& operator=(SeqPacket&&) = delete;
    ~SeqPacket();

    bool ok() const { return fd_ >= 0; }
    int fd() const { return fd_; }
    const std::string& error() const { return error_; }

    enum class Received { message, too_large, closed, failed, interrupted };
    // Blocks for the next datagram into `buffer` (its capacity is the limit); a larger one
    // is read, discarded and reported too_large.
    Received receive(std::vector<std::uint8_t>& buffer, std::size_t limit);
    // Whether a datagram is waiting, or arrives within wait_ms.
    bool pending(int wait_ms = 0) const;
    // False when gimbald went away (or the socket failed).
    bool send(std::span<const std::uint8_t> datagram);

  private:
    explicit SeqPacket(int fd, std::string error = {}) : fd_(fd), error_(std::move(error)) {}
    int fd_ = -1;
    std::string error_;
};

}  // namespace gimbal_track
