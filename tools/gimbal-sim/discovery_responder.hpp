// Answers a protocol's broadcast discovery (its registry entry's Simulator hook): a datagram
// that is a discovery request is answered with the gimbal's reply, sent to the requester's
// address at the reply port and, when different, to the request's source port (so clients
// that listen on an ephemeral port hear it too).
#pragma once

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <cstdint>
#include <span>
#include <vector>

namespace gimbal_sim {

class DiscoveryResponder {
  public:
    // Binds 0.0.0.0:port at once; throws on failure.
    using IsRequest = bool (*)(std::span<const std::uint8_t> datagram);
    DiscoveryResponder(boost::asio::io_context& io, std::uint16_t port, std::uint16_t reply_port,
                       IsRequest is_request, std::vector<std::uint8_t> reply);

    std::uint16_t port() const;
    void start();
    void stop();
    std::uint64_t answered() const { return answered_; }

  private:
    void do_receive();
    void answer(const boost::asio::ip::udp::endpoint& requester);

    boost::asio::ip::udp::socket socket_;
    std::uint16_t reply_port_;
    IsRequest is_request_;
    std::vector<std::uint8_t> reply_;
    std::array<std::uint8_t, 512> buffer_{};
    boost::asio::ip::udp::endpoint sender_;
    std::uint64_t answered_ = 0;
    bool stopped_ = false;
};

}  // namespace gimbal_sim
