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

// Fills the link until its queue refuses even after the writer had time to push what the
// kernel would take: the peer does not read, so the socket buffers are full too. Returns the
// packets accepted, in order.
std::vector<Bytes> fill(boost::asio::io_context& io, TcpLink& link) {
    std::vector<Bytes> sent;
    std::size_t index = 0;
    const auto next = [&] { return numbered_packet(index, 200 + (index * 37) % 900); };
    for (int round = 0; round < 10000; ++round) {
        for (Bytes packet = next(); link.send(packet); packet = next()) {
            sent.push_back(std::move(packet));
            ++index;
        }
        run_for(io, 20ms);
        Bytes probe = next();
        if (!link.send(probe)) break;  // still full: the kernel took nothing more
        sent.push_back(std::move(probe));
        ++index;
    }
    return sent;
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
    // An idle link writes at once, so the queue fills only behind a gimbal that does not read
    // (its socket buffers full). The exact bounds are unit-tested in test_send_queue.cpp.
    boost::asio::io_context io;
    TcpPeer peer(io, 0, 16, 4096);
    peer.set_reading(false);
    peer.accept();
    TcpLinkOptions options = loopback(peer.port());
    SECTION("by packet count") {
        options.queue = {.max_packets = 4, .max_bytes = 64 * 1024};
    }
    SECTION("by bytes") {
        options.queue = {.max_packets = 256, .max_bytes = 3000};
    }
    TcpLink link(io, options);
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));

    const std::vector<Bytes> sent = fill(io, link);
    CHECK_FALSE(link.send(numbered_packet(7, 3000)));  // more than either bound leaves room for
    CHECK(link.stats().tx_dropped >= 2);  // the refusal that ended fill(), and this one
    Bytes expected;
    for (const auto& p : sent) expected.insert(expected.end(), p.begin(), p.end());
    peer.set_reading(true);
    REQUIRE(run_until(
        io, [&] { return peer.received.size() >= expected.size(); }, 20000ms));
    CHECK(peer.received == expected);
    CHECK(link.send({0xFF}));  // drained: room again
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

TEST_CASE("tcp send_now behind a gimbal that does not read: the cease-fire goes ahead of the queue",
          "[tcp][safety]") {
    boost::asio::io_context io;
    TcpPeer peer(io, 0, 16, 4096);
    peer.set_reading(false);
    peer.accept();
    TcpLinkOptions options = loopback(peer.port());
    options.queue = {.max_packets = 8, .max_bytes = 64 * 1024};
    options.send_now_timeout_s = 0.05;
    TcpLink link(io, options);
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));
    const std::vector<Bytes> sent = fill(io, link);
    const std::uint64_t on_wire = link.stats().tx_bytes;
    const Bytes cease_fire(20, 0xEE);
    // The kernel takes (next to) nothing: written in time or not, the cease-fire is first in
    // line, and when the gimbal reads it follows the half-written packet.
    const bool in_time = link.send_now(cease_fire);
    INFO("send_now wrote it in time: " << in_time);
    peer.set_reading(true);
    std::size_t at = 0, first_unstarted = 0;
    while (first_unstarted < sent.size() && at < on_wire) at += sent[first_unstarted++].size();
    Bytes expected;
    for (std::size_t i = 0; i < first_unstarted; ++i)
        expected.insert(expected.end(), sent[i].begin(), sent[i].end());
    expected.insert(expected.end(), cease_fire.begin(), cease_fire.end());
    for (std::size_t i = first_unstarted + 1; i < sent.size(); ++i)  // one displaced
        expected.insert(expected.end(), sent[i].begin(), sent[i].end());
    REQUIRE(run_until(
        io, [&] { return peer.received.size() >= expected.size(); }, 20000ms));
    CHECK(peer.received == expected);
}

TEST_CASE("tcp send_now is false when not connected", "[tcp]") {
    boost::asio::io_context io;
    TcpLink link(io, loopback(unused_tcp_port(io)));
    LinkEvents events;
    events.start(link);
    CHECK_FALSE(link.send_now(numbered_packet(3, 20)));
    CHECK_FALSE(link.send_safety(numbered_packet(3, 20), [](bool) { FAIL("called"); }));
    run_for(io, 50ms);
}

TEST_CASE(
    "tcp cease-fire on a full queue: ahead of the queue, after the half-written packet, "
    "reported when written",
    "[tcp][safety]") {
    boost::asio::io_context io;
    TcpPeer peer(io, 0, 16, 4096);
    peer.set_reading(false);  // the gimbal stops reading
    peer.accept();
    TcpLinkOptions options = loopback(peer.port());
    options.queue = {.max_packets = 8, .max_bytes = 64 * 1024};
    TcpLink link(io, options);
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));

    const std::vector<Bytes> sent = fill(io, link);
    REQUIRE(sent.size() > 8);
    const std::uint64_t on_wire = link.stats().tx_bytes;
    const Bytes cease_fire(24, 0xEE);
    int calls = 0;
    bool written = false;
    REQUIRE(link.send_safety(cease_fire, [&](bool ok) {
        ++calls;
        written = ok;
    }));
    CHECK(link.stats().tx_displaced == 1);  // the queue was full: one packet made room
    run_for(io, 200ms);
    CHECK(calls == 0);  // not written while the gimbal does not read: not reported as sent
    CHECK(link.stats().tx_bytes == on_wire);

    peer.set_reading(true);
    REQUIRE(run_until(io, [&] { return calls == 1; }));
    CHECK(written);

    // Expected on the wire: every packet the kernel had taken (the one cut by the kernel
    // finished), the cease-fire, then the rest minus the oldest one not started (displaced).
    std::size_t at = 0, first_unstarted = 0;
    while (first_unstarted < sent.size() && at < on_wire) at += sent[first_unstarted++].size();
    Bytes expected;
    for (std::size_t i = 0; i < first_unstarted; ++i)
        expected.insert(expected.end(), sent[i].begin(), sent[i].end());
    expected.insert(expected.end(), cease_fire.begin(), cease_fire.end());
    for (std::size_t i = first_unstarted + 1; i < sent.size(); ++i)
        expected.insert(expected.end(), sent[i].begin(), sent[i].end());
    REQUIRE(run_until(
        io, [&] { return peer.received.size() >= expected.size(); }, 20000ms));
    CHECK(peer.received.size() == expected.size());
    CHECK(peer.received == expected);
    CHECK(events.downs == 0);
}

TEST_CASE("tcp cease-fire never displaces kept packets, and a disconnect reports it unsent",
          "[tcp][safety]") {
    boost::asio::io_context io;
    TcpPeer peer(io, 0, 16, 4096);
    peer.set_reading(false);
    peer.accept();
    TcpLinkOptions options = loopback(peer.port());
    options.queue = {.max_packets = 4, .max_bytes = 64 * 1024};
    TcpLink link(io, options);
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return link.connected() && peer.has_client(); }));
    // Kept packets only (laser commands), until the socket buffers and the queue are full.
    for (int round = 0; round < 10000; ++round) {
        std::size_t kept = 0;
        while (link.send_kept(numbered_packet(kept, 500))) ++kept;
        run_for(io, 20ms);
        if (!link.send_kept(numbered_packet(0, 500))) break;
    }
    std::vector<bool> outcomes;
    REQUIRE(link.send_safety(Bytes(24, 0xEE), [&](bool ok) { outcomes.push_back(ok); }));
    CHECK(link.stats().tx_displaced == 0);

    peer.close_client();  // the gimbal goes away before reading
    REQUIRE(run_until(io, [&] { return events.downs == 1; }));
    REQUIRE(run_until(io, [&] { return outcomes.size() == 1; }));
    CHECK(outcomes == std::vector<bool>{false});
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
