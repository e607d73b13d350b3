#include "udp_port.hpp"

#include <boost/asio/ip/address.hpp>

namespace gimbal_sim {

namespace asio = boost::asio;
using asio::ip::udp;

UdpPort::UdpPort(asio::io_context& io, const std::string& bind, std::uint16_t port,
                 BytesHandler on_bytes)
    : socket_(io, udp::endpoint(asio::ip::make_address(bind), port)),
      on_bytes_(std::move(on_bytes)) {}

void UdpPort::start() {
    stopped_ = false;
    receive();
}

void UdpPort::stop() {
    stopped_ = true;
    boost::system::error_code ignored;
    socket_.close(ignored);
}

void UdpPort::receive() {
    socket_.async_receive_from(asio::buffer(buffer_), from_,
                               [this](const boost::system::error_code& ec, std::size_t n) {
                                   if (stopped_ || ec == asio::error::operation_aborted) return;
                                   if (!ec && n > 0) {
                                       peer_ = from_;
                                       on_bytes_(std::span(buffer_.data(), n));
                                   }
                                   receive();
                               });
}

void UdpPort::write(std::span<const std::uint8_t> bytes) {
    if (!peer_ || bytes.empty() || stopped_) return;
    boost::system::error_code ignored;  // a lost datagram is UDP's way
    socket_.send_to(asio::buffer(bytes.data(), bytes.size()), *peer_, 0, ignored);
}

}  // namespace gimbal_sim
