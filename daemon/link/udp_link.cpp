#include "link/udp_link.hpp"

#include <boost/asio/ip/address.hpp>
#include <boost/asio/post.hpp>

#include "link/seconds.hpp"

namespace gimbald {

namespace asio = boost::asio;
using asio::ip::udp;

UdpLink::UdpLink(asio::io_context& io, UdpLinkOptions options)
    : io_(io),
      options_(std::move(options)),
      backoff_(BackoffOptions{options_.reconnect_min_s, options_.reconnect_max_s}),
      socket_(io),
      retry_(io),
      queue_(options_.queue) {}

UdpLink::~UdpLink() {
    stop();
}

std::string UdpLink::endpoint() const {
    if (options_.host.find(':') != std::string::npos)
        return "[" + options_.host + "]:" + std::to_string(options_.port);
    return options_.host + ":" + std::to_string(options_.port);
}

void UdpLink::start(DataHandler on_data, StateHandler on_state, ErrorHandler on_error) {
    stop();
    on_data_ = std::move(on_data);
    on_state_ = std::move(on_state);
    on_error_ = std::move(on_error);
    asio::post(io_, lifetime_.wrap([this] { open(); }));
}

void UdpLink::stop() {
    lifetime_.reset();
    retry_.cancel();
    boost::system::error_code ignored;
    socket_.close(ignored);
    for (auto& handler : queue_.clear()) (void)handler;  // stop(): no handler is called
    connected_ = false;
    writing_ = false;
}

void UdpLink::open() {
    boost::system::error_code ec;
    udp::resolver resolver(io_);
    const auto results = resolver.resolve(options_.host, std::to_string(options_.port), ec);
    if (ec || results.empty())
        return fail("resolve", "cannot resolve " + options_.host + ": " + ec.message());
    peer_ = *results.begin();
    socket_.open(peer_.protocol(), ec);
    if (!ec) socket_.bind(udp::endpoint(peer_.protocol(), options_.local_port.value_or(0)), ec);
    if (ec) {
        socket_.close(ec);
        return fail("bind", "cannot open the UDP socket: " + ec.message());
    }
    backoff_.reset();
    connected_ = true;
    if (opened_before_) ++stats_.reconnects;
    opened_before_ = true;
    receive();
    const auto generation = lifetime_.generation();
    if (on_state_) on_state_(true);
    if (generation == lifetime_.generation()) write_next();
}

void UdpLink::fail(std::string_view what, const std::string& detail) {
    const double delay = backoff_.next();
    const bool was_up = connected_;
    connected_ = false;
    writing_ = false;
    boost::system::error_code ignored;
    socket_.close(ignored);
    const auto generation = lifetime_.generation();
    for (auto& handler : queue_.clear())
        if (handler) asio::post(io_, lifetime_.wrap([h = std::move(handler)] { h(false); }));
    stats_.tx_dropped = queue_.dropped();
    if (on_error_) on_error_(what, detail + "; retrying in " + describe_seconds(delay));
    if (generation != lifetime_.generation()) return;
    if (was_up && on_state_) on_state_(false);
    if (generation != lifetime_.generation()) return;
    retry_.expires_after(seconds_to_duration(delay));
    retry_.async_wait(lifetime_.wrap([this](const boost::system::error_code& e) {
        if (!e) open();
    }));
}

void UdpLink::receive() {
    socket_.async_receive_from(
        asio::buffer(buffer_), from_,
        lifetime_.wrap([this](const boost::system::error_code& ec, std::size_t n) {
            if (ec) {
                // ICMP port unreachable from an earlier send: the gimbal is not there yet.
                if (ec == asio::error::connection_refused) return receive();
                return fail("read", "UDP receive failed: " + ec.message());
            }
            // Frames only from the configured host (any port: devices answer from theirs).
            if (from_.address() == peer_.address() && n > 0) {
                stats_.rx_bytes += n;
                stats_.last_rx = std::chrono::steady_clock::now();
                const auto generation = lifetime_.generation();
                if (on_data_) on_data_(std::span<const std::uint8_t>(buffer_.data(), n));
                if (generation != lifetime_.generation()) return;
            }
            receive();
        }));
}

void UdpLink::write_next() {
    if (writing_ || !connected_ || queue_.empty()) return;
    const auto next = queue_.next();
    writing_ = true;
    socket_.async_send_to(asio::buffer(next.data(), next.size()), peer_,
                          lifetime_.wrap([this, size = next.size()](
                                             const boost::system::error_code& ec, std::size_t) {
                              writing_ = false;
                              // A lost datagram is the network's business; the next one goes out
                              // regardless.
                              if (ec && ec != asio::error::connection_refused)
                                  return fail("write", "UDP send failed: " + ec.message());
                              stats_.tx_bytes += size;
                              ++stats_.tx_packets;
                              auto written = queue_.written(size);
                              if (written.safety && written.safety_done) written.safety_done(true);
                              write_next();
                          }));
}

bool UdpLink::send(std::vector<std::uint8_t> packet) {
    if (!connected_) return false;
    if (!queue_.push(std::move(packet))) {
        ++stats_.tx_dropped;
        return false;
    }
    write_next();
    return true;
}

bool UdpLink::send_kept(std::vector<std::uint8_t> packet) {
    if (!connected_) return false;
    if (!queue_.push(std::move(packet), SendQueue::Kind::kept)) {
        ++stats_.tx_dropped;
        return false;
    }
    write_next();
    return true;
}

bool UdpLink::send_safety(std::vector<std::uint8_t> packet, WrittenHandler on_written) {
    if (!connected_) return false;
    const auto displaced = queue_.push_safety(std::move(packet), std::move(on_written));
    stats_.tx_dropped += displaced;
    stats_.tx_displaced += displaced;
    write_next();
    return true;
}

bool UdpLink::send_now(std::span<const std::uint8_t> packet) {
    if (!connected_) return false;
    boost::system::error_code ec;
    const std::size_t n = socket_.send_to(asio::buffer(packet.data(), packet.size()), peer_, 0, ec);
    if (ec || n != packet.size()) return false;
    stats_.tx_bytes += n;
    ++stats_.tx_packets;
    return true;
}

}  // namespace gimbald
