// A gimbal's UDP broadcast discovery, as its protocol's registry entry says (the Orion SDK's:
// a zero-length CROWN_VERSION request): broadcast the request and take the source address of
// the first reply. One round per start(); the TcpLink repeats rounds with its backoff and
// re-discovers after every lost connection.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/address.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>

#include "link/lifetime.hpp"
#include "protocols/discovery.hpp"

namespace gimbald {

struct DiscoveryOptions {
    std::string address = "255.255.255.255";  // where the request goes (broadcast allowed)
    std::uint16_t port = 8745;                // the gimbal listens here
    std::uint16_t reply_port = 8746;  // we listen here; 0 = any free port (replies to source)
    double timeout_s = 1.5;           // a round without a reply fails after this long
    // What is asked and what answers: the gimbal's protocol's (empty: every round fails).
    gimbal::protocols::Discovery protocol;
};

class Discovery {
  public:
    // Exactly one of `gimbal` and a non-empty `error` is set.
    using Done =
        std::function<void(std::optional<boost::asio::ip::address> gimbal, std::string error)>;

    Discovery(boost::asio::io_context& io, DiscoveryOptions options);

    // Sends one request and waits for the first reply; `done` runs later from the io_context.
    void start(Done done);
    // Ends the round; `done` is not called.
    void cancel();

    const DiscoveryOptions& options() const { return options_; }

  private:
    void do_receive();
    void finish(std::optional<boost::asio::ip::address> gimbal, std::string error);

    boost::asio::io_context& io_;
    DiscoveryOptions options_;
    std::vector<std::uint8_t> request_;
    boost::asio::ip::udp::socket socket_;
    boost::asio::steady_timer timer_;
    Lifetime lifetime_;
    Done done_;
    std::array<std::uint8_t, 512> reply_{};
    boost::asio::ip::udp::endpoint sender_;
};

}  // namespace gimbald
