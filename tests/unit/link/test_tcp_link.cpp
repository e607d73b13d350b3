#include <catch2/catch.hpp>

#include <algorithm>
#include <boost/asio/connect.hpp>

#include "link/tcp_link.hpp"
#include "link_test_support.hpp"

using namespace link_test;
using gimbald::TcpLink;
using gimbald::TcpLinkOptions;

namespace {

TcpLinkOptions loopback(std::uint16_t port) {
    TcpLinkOptions options;
    options.host = "127.0.0.1";
    options.port = port;
    options.connect_timeout_s = 2.0;
    options.reconnect_min_s = 0.02;
    options.reconnect_max_s = 0.1;
    options.silence_timeout_s = 0.0;
    return options;
}

gimbald::Backoff seeded(const TcpLinkOptions& o) {
    return gimbald::Backoff({.min_s = o.reconnect_min_s, .max_s = o.reconnect_max_s}, 1u);
}

Bytes numbered_packet(std::size_t index, std::size_t size) {
    Bytes packet(size);
    for (std::size_t i = 0; i < size; ++i) packet[i] = static_cast<std::uint8_t>(index * 7 + i);
    return packet;
}

}  // namespace

TEST_CASE("tcp link connects and carries bytes both ways", "[tcp]") {
    boost::asio::io_context io;
    TcpPeer peer(io);
    peer.accept();
    TcpLink link(io, loopback(peer.port()));
    CHECK(link.type() == "tcp");
    CHECK(link.endpoint() == "127.0.0.1:" + std::to_string(peer.port()));

    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));
    CHECK(events.ups == 1);
    CHECK(events.errors.empty());

    const Bytes to_gimbal{0xD0, 0x0D, 0x01, 0x00, 0x00, 0x0A};
    CHECK(link.send(to_gimbal));
    REQUIRE(run_until(io, [&] { return peer.received.size() >= to_gimbal.size(); }));
    CHECK(peer.received == to_gimbal);

    const Bytes from_gimbal{9, 8, 7, 6, 0, 255};
    peer.write(from_gimbal);
    REQUIRE(run_until(io, [&] { return events.received.size() >= from_gimbal.size(); }));
    CHECK(events.received == from_gimbal);

    const gimbald::LinkStats& stats = link.stats();
    CHECK(stats.tx_bytes == to_gimbal.size());
    CHECK(stats.tx_packets == 1);
    CHECK(stats.rx_bytes == from_gimbal.size());
    CHECK(stats.last_rx.has_value());
    CHECK(stats.reconnects == 0);
    CHECK(stats.tx_dropped == 0);
}

TEST_CASE("tcp link retries a refused connect until the server appears", "[tcp]") {
    boost::asio::io_context io;
    const std::uint16_t port = unused_tcp_port(io);
    TcpLinkOptions options = loopback(port);
    TcpLink link(io, options, seeded(options));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return events.count_errors("connect") >= 3; }));
    CHECK_FALSE(link.connected());
    CHECK(events.ups == 0);
    CHECK(events.downs == 0);  // never connected, so never disconnected
    CHECK_THAT(events.error_detail("connect"), Catch::Contains("retrying in"));

    TcpPeer peer(io, port);
    peer.accept();
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));
    CHECK(events.ups == 1);
    CHECK(link.stats().reconnects == 0);  // the first successful connect is not a reconnect
}

TEST_CASE("tcp connect that hangs is cut off by the connect timeout", "[tcp]") {
    boost::asio::io_context io;
    // A listener whose accept queue is full: the kernel drops further SYNs, so a connect
    // neither succeeds nor fails by itself.
    TcpPeer peer(io, 0, 0);
    boost::asio::ip::tcp::socket filler(io);
    filler.connect({boost::asio::ip::make_address("127.0.0.1"), peer.port()});

    TcpLinkOptions options = loopback(peer.port());
    options.connect_timeout_s = 0.2;
    TcpLink link(io, options, seeded(options));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return events.count_errors("connect") >= 2; }));
    CHECK_THAT(events.error_detail("connect"), Catch::Contains("within"));
    CHECK_FALSE(link.connected());
    CHECK(events.ups == 0);
}

TEST_CASE("tcp link reconnects after the server closes and listens again", "[tcp]") {
    boost::asio::io_context io;
    auto peer = std::make_unique<TcpPeer>(io);
    const std::uint16_t port = peer->port();
    peer->accept();
    TcpLinkOptions options = loopback(port);
    TcpLink link(io, options, seeded(options));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer->has_client(); }));

    peer->close_client();
    peer->close_listener();
    REQUIRE(run_until(io, [&] { return events.downs == 1; }));
    CHECK_FALSE(link.connected());
    CHECK(events.count_errors("closed") == 1);
    CHECK_FALSE(link.send({1}));
    REQUIRE(run_until(io, [&] { return events.count_errors("connect") >= 1; }));  // refused

    peer = std::make_unique<TcpPeer>(io, port);
    peer->accept();
    REQUIRE(run_until(io, [&] { return events.ups == 2 && peer->has_client(); }));
    CHECK(link.stats().reconnects == 1);

    CHECK(link.send({4, 5, 6}));
    REQUIRE(run_until(io, [&] { return peer->received.size() >= 3; }));
    CHECK(peer->received == Bytes{4, 5, 6});
}

TEST_CASE("tcp link drops a silent peer and reconnects", "[tcp]") {
    boost::asio::io_context io;
    TcpPeer peer(io);
    peer.accept();
    TcpLinkOptions options = loopback(peer.port());
    options.silence_timeout_s = 0.2;
    TcpLink link(io, options, seeded(options));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return events.ups == 1 && peer.has_client(); }));

    peer.accept();  // for the reconnect
    REQUIRE(run_until(io, [&] { return events.downs == 1; }));
    CHECK(events.count_errors("silence") == 1);
    REQUIRE(run_until(io, [&] { return peer.closed_by_link == 1; }));  // the link closed it

    REQUIRE(run_until(io, [&] { return events.ups == 2 && link.connected(); }));
    CHECK(peer.accepted == 2);
    CHECK(link.stats().reconnects == 1);
}

TEST_CASE("tcp send is refused when not connected", "[tcp]") {
    boost::asio::io_context io;
    const std::uint16_t port = unused_tcp_port(io);
    TcpLink link(io, loopback(port));
    CHECK_FALSE(link.send({1, 2, 3}));
    LinkEvents events;
    events.start(link);
    CHECK_FALSE(link.send({1, 2, 3}));
    REQUIRE(run_until(io, [&] { return events.count_errors("connect") >= 1; }));
    CHECK_FALSE(link.send({1, 2, 3}));
    CHECK(link.stats().tx_dropped == 3);
    CHECK(link.stats().tx_bytes == 0);
}

TEST_CASE("tcp send is refused when the queue is full", "[tcp]") {
    boost::asio::io_context io;
    TcpPeer peer(io);
    peer.accept();
    TcpLinkOptions options = loopback(peer.port());
    TcpLink link(io, options);
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));

    SECTION("by packet count") {
        // Nothing is written until the io_context runs, so the queue fills deterministically.
        for (std::size_t i = 0; i < options.queue.max_packets; ++i) {
            REQUIRE(link.send({static_cast<std::uint8_t>(i)}));
        }
        CHECK_FALSE(link.send({0xFF}));
        CHECK(link.stats().tx_dropped == 1);
        REQUIRE(run_until(io, [&] { return peer.received.size() >= options.queue.max_packets; }));
        CHECK(peer.received.size() == options.queue.max_packets);
        CHECK(link.send({0xFF}));  // drained: room again
    }
    SECTION("by bytes") {
        const std::size_t big = options.queue.max_bytes / 2 + 1;
        CHECK(link.send(Bytes(big, 0xAA)));
        CHECK_FALSE(link.send(Bytes(big, 0xBB)));
        CHECK(link.send(Bytes(options.queue.max_bytes - big, 0xCC)));  // exactly full
        CHECK_FALSE(link.send({0xDD}));
        CHECK(link.stats().tx_dropped == 2);
        REQUIRE(run_until(io, [&] { return peer.received.size() >= options.queue.max_bytes; }));
        CHECK(peer.received.size() == options.queue.max_bytes);
    }
}

TEST_CASE("tcp packets are written whole and in order under backpressure", "[tcp]") {
    boost::asio::io_context io;
    TcpPeer peer(io, 0, 16, 4096);
    peer.set_reading(false);  // the gimbal is slow: the link must queue and wait
    peer.accept();
    TcpLink link(io, loopback(peer.port()));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));

    Bytes expected;
    std::size_t index = 0;
    bool refused = false;
    // Send until the socket buffers and then the queue are full (sizes vary to cut packets
    // at arbitrary points of the kernel's buffers).
    while (!refused && expected.size() < 64u * 1024 * 1024) {
        Bytes packet = numbered_packet(index, 100 + (index * 37) % 1400);
        if (link.send(packet)) {
            expected.insert(expected.end(), packet.begin(), packet.end());
            ++index;
        } else {
            refused = true;
        }
        if (index % 64 == 0) io.poll();
    }
    REQUIRE(refused);  // backpressure reached the queue
    CHECK(link.stats().tx_dropped == 1);

    peer.set_reading(true);
    for (int extra = 0; extra < 200; ++extra, ++index) {
        Bytes packet = numbered_packet(index, 1 + (index * 53) % 1500);
        REQUIRE(run_until(io, [&] { return link.send(packet); }));
        expected.insert(expected.end(), packet.begin(), packet.end());
    }
    REQUIRE(run_until(
        io, [&] { return peer.received.size() >= expected.size(); }, 20000ms));
    CHECK(peer.received.size() == expected.size());
    CHECK(peer.received == expected);
    CHECK(link.stats().tx_packets == index);
    CHECK(link.stats().tx_bytes == expected.size());
}

TEST_CASE("tcp send_now writes the queue and then the packet at once", "[tcp]") {
    boost::asio::io_context io;
    TcpPeer peer(io);
    peer.accept();
    TcpLink link(io, loopback(peer.port()));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));

    const Bytes a = numbered_packet(1, 300);
    const Bytes b = numbered_packet(2, 500);
    const Bytes cease_fire = numbered_packet(3, 20);
    REQUIRE(link.send(a));
    REQUIRE(link.send(b));
    link.send_now(cease_fire);  // no io_context run in between: written synchronously
    CHECK(link.stats().tx_packets == 3);
    CHECK(link.stats().tx_bytes == a.size() + b.size() + cease_fire.size());

    // Copied into a buffer of the final size: growing `expected` by insert() makes GCC 12
    // -O3 on aarch64 report a false -Warray-bounds inside vector's reallocation.
    Bytes expected(a.size() + b.size() + cease_fire.size());
    auto at = std::copy(a.begin(), a.end(), expected.begin());
    at = std::copy(b.begin(), b.end(), at);
    std::copy(cease_fire.begin(), cease_fire.end(), at);
    REQUIRE(run_until(io, [&] { return peer.received.size() >= expected.size(); }));
    CHECK(peer.received == expected);
}

TEST_CASE("tcp link stays silent after stop and may be destroyed with work pending", "[tcp]") {
    boost::asio::io_context io;
    TcpPeer peer(io);
    peer.accept();
    {
        TcpLink link(io, loopback(peer.port()));
        LinkEvents events;
        events.start(link);
        REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));
        CHECK(link.send({1, 2, 3}));
        peer.write({4, 5, 6});
        link.stop();
        CHECK_FALSE(link.connected());
        peer.close_client();
        run_for(io, 100ms);
        CHECK(events.received.empty());
        CHECK(events.downs == 0);
        CHECK(events.errors.empty());
        CHECK(peer.received.empty());  // the queued packet was discarded, not written
    }
    {
        // Destroyed right after start(): the posted first attempt must not touch it.
        TcpLink link(io, loopback(peer.port()));
        LinkEvents events;
        events.start(link);
    }
    run_for(io, 50ms);
}
