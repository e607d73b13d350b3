// TCP link to a gimbal (or gimbal-sim): non-blocking resolve + connect with a timeout,
// TCP_NODELAY and SO_KEEPALIVE, reconnect forever with backoff, silence watchdog. With host
// "discover" every connection attempt starts with the protocol's UDP broadcast discovery.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>

#include "link/backoff.hpp"
#include "link/discovery.hpp"
#include "link/link_config.hpp"
#include "link/stream_link.hpp"

namespace gimbald {

// The `link` section of type "tcp" (link_config.hpp: host or "discover", port, timeouts - the
// connect timeout covers resolve + connect; silence 0 disables - and where discovery asks)
// and what the daemon adds.
struct TcpLinkOptions : gimbal::daemon::TcpLink {
    explicit TcpLinkOptions(gimbal::daemon::TcpLink config = {}) : TcpLink(std::move(config)) {}

    double discover_timeout_s = 1.5;  // a discovery round without a reply fails
    // What discovery asks and what answers: the gimbal's protocol's (registry entry).
    gimbal::protocols::Discovery discovery;
    SendQueueLimits queue;
    double send_now_timeout_s = 0.25;
    // SO_SNDBUF of the connection. The kernel would otherwise grow it to megabytes while the
    // gimbal does not read, and a cease-fire that goes ahead of our queue would still wait
    // behind all of that (contract section 14). Commands are a few KB/s: this is plenty.
    int kernel_send_buffer = 16 * 1024;
};

class TcpLink final : public StreamLink<boost::asio::ip::tcp::socket> {
  public:
    TcpLink(boost::asio::io_context& io, TcpLinkOptions options);
    // `backoff` replaces the one built from reconnect_min_s/max_s (tests pass a seeded one).
    TcpLink(boost::asio::io_context& io, TcpLinkOptions options, Backoff backoff);

    std::string type() const override { return "tcp"; }
    // "host:port"; in discovery mode the discovered address, or "discover:port" before that.
    std::string endpoint() const override;

    bool discovery_mode() const { return discovery_.has_value(); }

  private:
    void open() override;
    void close_attempt() override;
    void connect(const std::string& host);
    void on_resolved(const boost::system::error_code& ec,
                     const boost::asio::ip::tcp::resolver::results_type& endpoints);
    void on_connected(const boost::system::error_code& ec);

    TcpLinkOptions options_;
    boost::asio::ip::tcp::resolver resolver_;
    boost::asio::steady_timer connect_timer_;
    std::optional<Discovery> discovery_;
    std::string target_host_;  // the host of the current/last attempt
};

}  // namespace gimbald
