// UDP link (contract section 19): datagrams to host:port from local_port (or an ephemeral
// port), and only datagrams from that host are taken (each one is whole frames, handed up as
// they come). Up once the socket is open - UDP has no connection: a silent gimbal shows as
// `stale`. A failing socket (the host does not resolve, the port is taken) is retried with
// the backoff. Packets go out in order, one datagram each, cease-fires first.
#pragma once

#include <array>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>

#include "link/backoff.hpp"
#include "link/lifetime.hpp"
#include "link/link.hpp"
#include "link/link_config.hpp"
#include "link/send_queue.hpp"

namespace gimbald {

// The `link` section of type "udp" (link_config.hpp; no local_port: an ephemeral port) and
// what the daemon adds.
struct UdpLinkOptions : gimbal::daemon::UdpLink {
    explicit UdpLinkOptions(gimbal::daemon::UdpLink config = {}) : UdpLink(std::move(config)) {}
    SendQueueLimits queue;
};

class UdpLink final : public Link {
  public:
    UdpLink(boost::asio::io_context& io, UdpLinkOptions options);
    ~UdpLink() override;

    void start(DataHandler on_data, StateHandler on_state, ErrorHandler on_error) override;
    void stop() override;
    bool connected() const override { return connected_; }
    bool send(std::vector<std::uint8_t> packet) override;
    bool send_kept(std::vector<std::uint8_t> packet) override;
    bool send_safety(std::vector<std::uint8_t> packet, WrittenHandler on_written) override;
    bool send_now(std::span<const std::uint8_t> packet) override;
    const LinkStats& stats() const override { return stats_; }
    std::string type() const override { return "udp"; }
    std::string endpoint() const override;  // "192.168.1.30:14570"

  private:
    void open();
    void fail(std::string_view what, const std::string& detail);
    void receive();
    void write_next();

    boost::asio::io_context& io_;
    UdpLinkOptions options_;
    Backoff backoff_;
    boost::asio::ip::udp::socket socket_;
    boost::asio::ip::udp::endpoint peer_;
    boost::asio::ip::udp::endpoint from_;
    std::array<std::uint8_t, 65536> buffer_{};
    boost::asio::steady_timer retry_;
    Lifetime lifetime_;
    SendQueue queue_;
    DataHandler on_data_;
    StateHandler on_state_;
    ErrorHandler on_error_;
    LinkStats stats_;
    bool connected_ = false;
    bool writing_ = false;
    bool opened_before_ = false;
};

}  // namespace gimbald
