// Non-blocking UDP datagrams to one destination (unicast or multicast, TTL, outbound
// interface) for the video outputs. A send never waits: a full socket buffer (EAGAIN)
// drops the datagram and counts it; an error such as "no route to host" or "network
// unreachable" is logged once (video_output_error), counted, and sending pauses for
// retry_s before the next try, so a dead route costs one syscall per retry_s, not per
// datagram; the first datagram that goes out again is logged (video_output_ok).
#pragma once

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

namespace gimbald::video {

struct UdpSenderStats {
    std::uint64_t datagrams = 0;
    std::uint64_t bytes = 0;
    std::uint64_t dropped_full = 0;   // EAGAIN: the socket buffer was full
    std::uint64_t dropped_error = 0;  // a send failed, or came during the pause after one
    std::uint64_t errors = 0;         // failed sends (each starts a pause)
    std::string last_error;
};

class UdpSender {
  public:
    // Throws std::invalid_argument when host or iface is not an IP address.
    UdpSender(boost::asio::io_context& io, const std::string& host, std::uint16_t port,
              std::optional<int> ttl, const std::string& iface, double retry_s,
              nlohmann::json log_fields);

    // True when the datagram went out.
    bool send(std::span<const std::uint8_t> datagram);

    const UdpSenderStats& stats() const { return stats_; }
    const boost::asio::ip::udp::endpoint& destination() const { return destination_; }

  private:
    bool open();
    void failed(const boost::system::error_code& ec);

    boost::asio::ip::udp::socket socket_;
    boost::asio::ip::udp::endpoint destination_;
    std::optional<int> ttl_;
    std::optional<boost::asio::ip::address> iface_;
    std::chrono::steady_clock::duration retry_;
    std::optional<std::chrono::steady_clock::time_point> paused_until_;
    bool failing_ = false;
    std::uint64_t dropped_since_failure_ = 0;
    nlohmann::json log_fields_;
    UdpSenderStats stats_;
};

}  // namespace gimbald::video
