#include <catch2/catch.hpp>

#include <boost/asio/ip/udp.hpp>

#include "link/discovery.hpp"
#include "link/tcp_link.hpp"
#include "link_test_support.hpp"
#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/registry.hpp"

using namespace link_test;
namespace asio = boost::asio;
using asio::ip::udp;

namespace {

// Plays the gimbal's discovery side on 127.0.0.1: records every request and answers from its
// own address, like the Orion, after ignoring the first `ignore` requests. A junk datagram
// goes out before every real reply.
class DiscoveryResponder {
  public:
    DiscoveryResponder(asio::io_context& io, int ignore)
        : socket_(io, udp::endpoint(asio::ip::make_address("127.0.0.1"), 0)), ignore_(ignore) {
        do_receive();
    }
    std::uint16_t port() const { return socket_.local_endpoint().port(); }

    std::vector<Bytes> requests;

  private:
    void do_receive() {
        socket_.async_receive_from(
            asio::buffer(buffer_), sender_,
            [this](const boost::system::error_code& ec, std::size_t n) {
                if (ec) return;
                requests.emplace_back(buffer_.begin(),
                                      buffer_.begin() + static_cast<std::ptrdiff_t>(n));
                if (static_cast<int>(requests.size()) > ignore_) {
                    const Bytes junk{'h', 'i'};
                    socket_.send_to(asio::buffer(junk), sender_);
                    const std::uint8_t version[] = {'1', '.', '3', 0};
                    socket_.send_to(asio::buffer(gimbal::orion::frame_bytes(
                                        gimbal::orion::pkt::crown_version, version)),
                                    sender_);
                }
                do_receive();
            });
    }

    udp::socket socket_;
    int ignore_;
    std::array<std::uint8_t, 512> buffer_{};
    udp::endpoint sender_;
};

// The Orion's discovery: what these tests answer.
gimbal::protocols::Discovery orion_discovery() {
    return gimbal::protocols::entry(gimbal::protocols::ProtocolId::orion).discovery;
}

gimbald::TcpLinkOptions discovering(std::uint16_t tcp_port, std::uint16_t discover_port) {
    gimbald::TcpLinkOptions options;
    options.host = "discover";
    options.port = tcp_port;
    options.connect_timeout_s = 2.0;
    options.reconnect_min_s = 0.02;
    options.reconnect_max_s = 0.1;
    options.silence_timeout_s = 0.0;
    options.discover_address = "127.0.0.1";
    options.discover_port = discover_port;
    options.discover_reply_port = 0;
    options.discover_timeout_s = 0.2;
    options.discovery = orion_discovery();
    return options;
}

const Bytes crown_version_request{0xD0, 0x0D, 0x28, 0x00, 0x0B, 0xCA};

}  // namespace

TEST_CASE("discovery finds the gimbal's address from the first reply", "[discovery]") {
    asio::io_context io;
    DiscoveryResponder responder(io, 0);
    gimbald::Discovery discovery(io, {.address = "127.0.0.1",
                                      .port = responder.port(),
                                      .reply_port = 0,
                                      .timeout_s = 1.0,
                                      .protocol = orion_discovery()});
    std::optional<asio::ip::address> found;
    std::string error;
    bool done = false;
    discovery.start([&](std::optional<asio::ip::address> gimbal, std::string why) {
        found = gimbal;
        error = std::move(why);
        done = true;
    });
    REQUIRE(run_until(io, [&] { return done; }));
    REQUIRE(found.has_value());
    CHECK(found->to_string() == "127.0.0.1");
    CHECK(error.empty());
    REQUIRE(responder.requests.size() == 1);
    CHECK(responder.requests[0] == crown_version_request);
}

TEST_CASE("discovery reports a round without a reply", "[discovery]") {
    asio::io_context io;
    DiscoveryResponder responder(io, 1000);
    gimbald::Discovery discovery(io, {.address = "127.0.0.1",
                                      .port = responder.port(),
                                      .reply_port = 0,
                                      .timeout_s = 0.1,
                                      .protocol = orion_discovery()});
    std::optional<asio::ip::address> found;
    std::string error;
    bool done = false;
    discovery.start([&](std::optional<asio::ip::address> gimbal, std::string why) {
        found = gimbal;
        error = std::move(why);
        done = true;
    });
    REQUIRE(run_until(io, [&] { return done; }));
    CHECK_FALSE(found.has_value());
    CHECK_THAT(error, Catch::Contains("no reply"));
}

TEST_CASE("discovery of a protocol without one fails every round and sends nothing",
          "[discovery]") {
    asio::io_context io;
    DiscoveryResponder responder(io, 0);
    gimbald::Discovery discovery(io, {.address = "127.0.0.1",
                                      .port = responder.port(),
                                      .reply_port = 0,
                                      .timeout_s = 1.0,
                                      .protocol = {}});
    std::optional<asio::ip::address> found;
    std::string error;
    bool done = false;
    discovery.start([&](std::optional<asio::ip::address> gimbal, std::string why) {
        found = gimbal;
        error = std::move(why);
        done = true;
    });
    REQUIRE(run_until(io, [&] { return done; }));
    CHECK_FALSE(found.has_value());
    CHECK(error == "this protocol has no broadcast discovery");
    run_for(io, 50ms);
    CHECK(responder.requests.empty());
}

TEST_CASE("tcp link discovers the gimbal, connects, and re-discovers after a loss",
          "[discovery][tcp]") {
    asio::io_context io;
    DiscoveryResponder responder(io, 2);  // the first two rounds go unanswered
    TcpPeer peer(io);
    peer.accept();
    gimbald::TcpLink link(io, discovering(peer.port(), responder.port()));
    CHECK(link.discovery_mode());
    CHECK(link.endpoint() == "discover:" + std::to_string(peer.port()));

    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));
    CHECK(events.count_errors("discover") == 2);
    CHECK(responder.requests.size() == 3);
    for (const Bytes& request : responder.requests) CHECK(request == crown_version_request);
    CHECK(link.endpoint() == "127.0.0.1:" + std::to_string(peer.port()));

    CHECK(link.send({1, 2, 3}));
    REQUIRE(run_until(io, [&] { return peer.received.size() >= 3; }));
    CHECK(peer.received == Bytes{1, 2, 3});

    peer.accept();
    peer.close_client();
    REQUIRE(run_until(io, [&] { return events.downs == 1; }));
    REQUIRE(run_until(io, [&] { return events.ups == 2 && link.connected(); }));
    CHECK(responder.requests.size() == 4);  // discovered again before reconnecting
    CHECK(link.stats().reconnects == 1);
}
