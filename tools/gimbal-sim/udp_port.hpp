// gimbal-sim's UDP endpoint (--udp PORT), as a MAVLink gimbal device on a network: it takes
// datagrams from anyone and sends what the gimbal says to the latest sender, one datagram
// per burst of frames. Silent until someone has sent.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

namespace gimbal_sim {

class UdpPort {
  public:
    using BytesHandler = std::function<void(std::span<const std::uint8_t>)>;
    // Binds bind:port (0: a free port); throws on failure (startup error).
    UdpPort(boost::asio::io_context& io, const std::string& bind, std::uint16_t port,
            BytesHandler on_bytes);

    void start();
    void stop();
    void write(std::span<const std::uint8_t> bytes);
    boost::asio::ip::udp::endpoint local_endpoint() const { return socket_.local_endpoint(); }

  private:
    void receive();

    boost::asio::ip::udp::socket socket_;
    BytesHandler on_bytes_;
    std::array<std::uint8_t, 65536> buffer_{};
    boost::asio::ip::udp::endpoint from_;
    std::optional<boost::asio::ip::udp::endpoint> peer_;
    bool stopped_ = false;
};

}  // namespace gimbal_sim
