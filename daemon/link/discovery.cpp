#include "link/discovery.hpp"

#include <boost/asio/buffer.hpp>
#include <boost/asio/post.hpp>

#include "link/seconds.hpp"

namespace gimbald {

namespace asio = boost::asio;
using asio::ip::udp;

Discovery::Discovery(asio::io_context& io, DiscoveryOptions options)
    : io_(io),
      options_(std::move(options)),
      request_(options_.protocol ? options_.protocol.request() : std::vector<std::uint8_t>{}),
      socket_(io),
      timer_(io) {}

void Discovery::start(Done done) {
    cancel();
    done_ = std::move(done);
    const std::string target = options_.address + ":" + std::to_string(options_.port);

    // Setup errors are reported like a missing reply: later, from the io_context.
    auto fail_later = [this](std::string error) {
        asio::post(io_, lifetime_.wrap([this, error] { finish(std::nullopt, error); }));
    };
    if (!options_.protocol) return fail_later("this protocol has no broadcast discovery");
    boost::system::error_code ec;
    const asio::ip::address address = asio::ip::make_address(options_.address, ec);
    if (ec) return fail_later("bad discover_address \"" + options_.address + "\"");
    if (socket_.open(udp::v4(), ec); ec) return fail_later("udp socket: " + ec.message());
    socket_.set_option(asio::socket_base::reuse_address(true), ec);
    if (socket_.set_option(asio::socket_base::broadcast(true), ec); ec) {
        return fail_later("SO_BROADCAST: " + ec.message());
    }
    if (socket_.bind(udp::endpoint(asio::ip::address_v4::any(), options_.reply_port), ec); ec) {
        return fail_later("bind udp port " + std::to_string(options_.reply_port) + ": " +
                          ec.message());
    }
    socket_.send_to(asio::buffer(request_), udp::endpoint(address, options_.port), 0, ec);
    if (ec) return fail_later("send to " + target + ": " + ec.message());

    timer_.expires_after(seconds_to_duration(options_.timeout_s));
    timer_.async_wait(lifetime_.wrap([this, target](const boost::system::error_code& wait_ec) {
        if (!wait_ec) {
            finish(std::nullopt,
                   "no reply to " + target + " within " + describe_seconds(options_.timeout_s));
        }
    }));
    do_receive();
}

void Discovery::do_receive() {
    socket_.async_receive_from(
        asio::buffer(reply_), sender_,
        lifetime_.wrap([this](const boost::system::error_code& ec, std::size_t n) {
            if (ec) return finish(std::nullopt, "udp receive: " + ec.message());
            // Anything that is not the protocol's answer (a stray datagram) is ignored.
            if (!options_.protocol.is_reply({reply_.data(), n})) return do_receive();
            finish(sender_.address(), {});
        }));
}

void Discovery::cancel() {
    lifetime_.reset();
    boost::system::error_code ignored;
    socket_.close(ignored);
    timer_.cancel();
    done_ = nullptr;
}

void Discovery::finish(std::optional<asio::ip::address> gimbal, std::string error) {
    Done done = std::move(done_);
    cancel();
    if (done) done(std::move(gimbal), std::move(error));
}

}  // namespace gimbald
