// A connected UDP socket to gimbald. Connecting (rather than sendto) makes the kernel drop
// datagrams from any other address and report ICMP "port unreachable" as
// connection_refused, which is how gimbalctl tells "nothing listens" from "no reply yet".
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

namespace gimbalctl {

class UdpTransport {
  public:
    using DatagramHandler = std::function<void(std::string_view datagram)>;
    // A receive or send error other than cancellation; receiving goes on afterwards.
    using ErrorHandler = std::function<void(const boost::system::error_code& error)>;

    UdpTransport(boost::asio::io_context& io, DatagramHandler on_datagram, ErrorHandler on_error);

    // Resolves host (IPv4, IPv6 or name) and connects to the first address. False with a
    // message in `problem` when the name does not resolve or no socket can be opened.
    bool open(const std::string& host, std::uint16_t port, std::string& problem);

    // Sends one datagram and remembers it: if the address refuses it, the next resolved
    // address (if any) is tried with the same datagram.
    void send(const std::string& datagram);

    // Starts the receive loop; handlers are called from io_context::run().
    void start_receiving();
    void close();

    // "host:port" for messages.
    std::string peer() const;

  private:
    void do_receive();
    void on_receive(const boost::system::error_code& error, std::size_t length);
    bool connect_current(boost::system::error_code& error);
    // On connection_refused: move to the next address and resend; false when none is left.
    bool try_next_address();

    boost::asio::ip::udp::socket socket_;
    DatagramHandler on_datagram_;
    ErrorHandler on_error_;
    std::vector<boost::asio::ip::udp::endpoint> addresses_;
    std::size_t current_ = 0;
    std::string host_;
    std::uint16_t port_ = 0;
    std::string last_sent_;
    bool receiving_ = false;
    // Larger than any UDP payload, so no datagram is ever cut.
    std::array<char, 65536> buffer_{};
};

}  // namespace gimbalctl
