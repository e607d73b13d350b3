#include "discovery_responder.hpp"

#include <boost/asio/buffer.hpp>

namespace gimbal_sim {

namespace asio = boost::asio;
using asio::ip::udp;

DiscoveryResponder::DiscoveryResponder(asio::io_context& io, std::uint16_t port,
                                       std::uint16_t reply_port, IsRequest is_request,
                                       std::vector<std::uint8_t> reply)
    : socket_(io), reply_port_(reply_port), is_request_(is_request), reply_(std::move(reply)) {
    socket_.open(udp::v4());
    socket_.set_option(asio::socket_base::reuse_address(true));
    socket_.bind(udp::endpoint(asio::ip::address_v4::any(), port));
}

std::uint16_t DiscoveryResponder::port() const {
    return socket_.local_endpoint().port();
}

void DiscoveryResponder::start() {
    do_receive();
}

void DiscoveryResponder::stop() {
    stopped_ = true;
    boost::system::error_code ignored;
    socket_.close(ignored);
}

void DiscoveryResponder::do_receive() {
    socket_.async_receive_from(asio::buffer(buffer_), sender_,
                               [this](const boost::system::error_code& ec, std::size_t n) {
                                   if (stopped_) return;
                                   if (!ec && is_request_({buffer_.data(), n})) answer(sender_);
                                   do_receive();
                               });
}

void DiscoveryResponder::answer(const udp::endpoint& requester) {
    boost::system::error_code ec;
    const std::uint16_t reply_port = reply_port_ != 0 ? reply_port_ : requester.port();
    socket_.send_to(asio::buffer(reply_), udp::endpoint(requester.address(), reply_port), 0, ec);
    if (reply_port != requester.port()) socket_.send_to(asio::buffer(reply_), requester, 0, ec);
    ++answered_;
}

}  // namespace gimbal_sim
