#include "transport.hpp"

#include <boost/asio/buffer.hpp>
#include <boost/asio/error.hpp>
#include <boost/asio/ip/udp.hpp>

namespace gimbalctl {

namespace asio = boost::asio;
using asio::ip::udp;

UdpTransport::UdpTransport(asio::io_context& io, DatagramHandler on_datagram, ErrorHandler on_error)
    : socket_(io), on_datagram_(std::move(on_datagram)), on_error_(std::move(on_error)) {}

bool UdpTransport::open(const std::string& host, std::uint16_t port, std::string& problem) {
    host_ = host;
    port_ = port;
    boost::system::error_code error;
    udp::resolver resolver(socket_.get_executor());
    const auto results =
        resolver.resolve(host, std::to_string(port), udp::resolver::numeric_service, error);
    if (error) {
        problem = "cannot resolve " + host + ": " + error.message();
        return false;
    }
    for (const auto& result : results) addresses_.push_back(result.endpoint());
    if (addresses_.empty()) {
        problem = "cannot resolve " + host + ": no address";
        return false;
    }
    for (current_ = 0; current_ < addresses_.size(); ++current_) {
        if (connect_current(error)) return true;
    }
    problem = "cannot open a socket to " + peer() + ": " + error.message();
    return false;
}

bool UdpTransport::connect_current(boost::system::error_code& error) {
    socket_.close(error);
    socket_.open(addresses_[current_].protocol(), error);
    if (!error) socket_.connect(addresses_[current_], error);
    return !error;
}

void UdpTransport::send(const std::string& datagram) {
    last_sent_ = datagram;
    boost::system::error_code error;
    socket_.send(asio::buffer(datagram), 0, error);
    // A refusal of an earlier datagram can surface here instead of on receive.
    if (error == asio::error::connection_refused && try_next_address()) {
        // Reconnecting cancelled the receive in flight; start a fresh one.
        if (receiving_) do_receive();
        return;
    }
    if (error) on_error_(error);
}

bool UdpTransport::try_next_address() {
    while (current_ + 1 < addresses_.size()) {
        ++current_;
        boost::system::error_code error;
        if (!connect_current(error)) continue;
        socket_.send(asio::buffer(last_sent_), 0, error);
        if (!error) return true;
    }
    return false;
}

void UdpTransport::start_receiving() {
    receiving_ = true;
    do_receive();
}

void UdpTransport::close() {
    boost::system::error_code ignored;
    socket_.close(ignored);
}

std::string UdpTransport::peer() const {
    if (addresses_.empty()) return host_ + ":" + std::to_string(port_);
    const auto& address = addresses_[current_ < addresses_.size() ? current_ : 0];
    const std::string ip = address.address().to_string();
    return (address.address().is_v6() ? "[" + ip + "]" : ip) + ":" + std::to_string(port_);
}

void UdpTransport::do_receive() {
    socket_.async_receive(asio::buffer(buffer_),
                          [this](const boost::system::error_code& error, std::size_t length) {
                              on_receive(error, length);
                          });
}

void UdpTransport::on_receive(const boost::system::error_code& error, std::size_t length) {
    if (error == asio::error::operation_aborted || !socket_.is_open()) return;
    if (error == asio::error::connection_refused && try_next_address()) {
        // This completion was the only receive in flight; continue on the new socket.
        do_receive();
        return;
    }
    if (error) {
        on_error_(error);
    } else {
        on_datagram_(std::string_view(buffer_.data(), length));
    }
    if (socket_.is_open()) do_receive();
}

}  // namespace gimbalctl
