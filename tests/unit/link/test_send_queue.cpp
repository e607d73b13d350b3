// The stream links' outgoing queue (contract section 14): a cease-fire goes ahead of
// everything queued, after a half-written packet, and is never refused for a full queue.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "link/send_queue.hpp"

using gimbald::SendQueue;
using gimbald::SendQueueLimits;
using Bytes = std::vector<std::uint8_t>;

namespace {

Bytes packet(std::uint8_t tag, std::size_t size) {
    return Bytes(size, tag);
}

// Writes everything in chunks of at most `chunk` bytes; returns the bytes in wire order and
// the tags of the safety packets whose handlers ran, in order.
struct Drained {
    Bytes wire;
    std::vector<int> safety_done;
};
Drained drain(SendQueue& q, std::size_t chunk, std::vector<int>& done) {
    Drained out;
    while (!q.empty()) {
        const auto next = q.next();
        const std::size_t n = std::min(chunk, next.size());
        out.wire.insert(out.wire.end(), next.begin(), next.begin() + static_cast<long>(n));
        auto w = q.written(n);
        if (w.safety_done) w.safety_done(true);
    }
    out.safety_done = done;
    return out;
}

// The packet tags in wire order, one per run of equal bytes (packets use distinct tags).
std::string order(const Bytes& wire) {
    std::string out;
    for (std::size_t i = 0; i < wire.size(); ++i)
        if (i == 0 || wire[i] != wire[i - 1]) out += static_cast<char>(wire[i]);
    return out;
}

}  // namespace

TEST_CASE("send queue: normal packets go out in order, bounded by packets and bytes",
          "[send_queue]") {
    SendQueue q(SendQueueLimits{.max_packets = 3, .max_bytes = 100});
    CHECK(q.push(packet('a', 10)));
    CHECK(q.push(packet('b', 10)));
    CHECK(q.push(packet('c', 10)));
    CHECK_FALSE(q.push(packet('d', 1)));  // 3 packets
    CHECK(q.packets() == 3);
    CHECK(q.bytes() == 30);
    std::vector<int> done;
    CHECK(order(drain(q, 7, done).wire) == "abc");
    CHECK(q.bytes() == 0);

    CHECK(q.push(packet('e', 60)));
    CHECK_FALSE(q.push(packet('f', 41)));  // 101 bytes
    CHECK(q.push(packet('f', 40)));        // exactly 100
    CHECK(q.push(Bytes{}));                // empty: accepted, nothing queued
    CHECK(q.packets() == 2);
}

TEST_CASE("send queue: a safety packet goes ahead of everything not yet started", "[send_queue]") {
    SendQueue q(SendQueueLimits{});
    REQUIRE(q.push(packet('a', 10)));
    REQUIRE(q.push(packet('b', 10)));
    std::vector<int> done;
    CHECK(q.push_safety(packet('S', 5), [&](bool ok) { done.push_back(ok ? 'S' : -'S'); }) == 0);
    REQUIRE(q.push(packet('c', 10)));
    CHECK(q.push_safety(packet('T', 5), [&](bool ok) { done.push_back(ok ? 'T' : -'T'); }) == 0);
    const auto d = drain(q, 3, done);
    CHECK(order(d.wire) == "STabc");  // safety first, in their own order
    CHECK(d.safety_done == std::vector<int>{'S', 'T'});
}

TEST_CASE("send queue: a half-written packet is finished before the safety packet",
          "[send_queue]") {
    SendQueue q(SendQueueLimits{});
    REQUIRE(q.push(packet('a', 10)));
    REQUIRE(q.push(packet('b', 10)));
    // 4 bytes of 'a' are on the wire.
    REQUIRE(q.next().size() == 10);
    CHECK_FALSE(q.written(4).packet_done);
    CHECK(q.half_written());
    std::vector<int> done;
    q.push_safety(packet('S', 5), [&](bool ok) { done.push_back(ok ? 1 : 0); });
    CHECK(q.next().size() == 6);  // the rest of 'a' comes first
    CHECK(q.next()[0] == 'a');
    const auto d = drain(q, 4, done);
    CHECK(d.wire.size() == 6 + 5 + 10);
    CHECK(order(d.wire) == "aSb");
    CHECK(done == std::vector<int>{1});

    // A half-written safety packet is finished before the next one, too.
    q.push(packet('c', 10));
    q.push_safety(packet('S', 8), nullptr);
    CHECK_FALSE(q.written(3).packet_done);
    q.push_safety(packet('T', 8), nullptr);
    CHECK(q.next().size() == 5);
    CHECK(q.next()[0] == 'S');
}

TEST_CASE("send queue: a full queue makes room for safety by dropping the oldest normal packets",
          "[send_queue]") {
    SendQueue q(SendQueueLimits{.max_packets = 4, .max_bytes = 1000});
    REQUIRE(q.push(packet('a', 10)));
    REQUIRE(q.push(packet('b', 10)));
    REQUIRE(q.push(packet('c', 10), SendQueue::Kind::kept));  // a laser command
    REQUIRE(q.push(packet('d', 10)));
    REQUIRE_FALSE(q.push(packet('e', 10)));
    CHECK_FALSE(q.written(2).packet_done);  // 'a' is half written: it cannot be dropped
    std::vector<int> done;
    CHECK(q.push_safety(packet('S', 5), [&](bool ok) { done.push_back(ok ? 1 : 0); }) == 1);
    CHECK(q.displaced() == 1);
    CHECK(q.packets() == 4);
    const auto d = drain(q, 100, done);
    // 'b' made room; the kept 'c' (a laser command) stays and goes before the cease-fire.
    CHECK(order(d.wire) == "acSd");
    CHECK(done == std::vector<int>{1});
}

TEST_CASE("send queue: a cease-fire never overtakes a laser command queued before it",
          "[send_queue]") {
    SendQueue q(SendQueueLimits{});
    REQUIRE(q.push(packet('a', 10)));
    REQUIRE(q.push(packet('f', 10), SendQueue::Kind::kept));  // fire
    REQUIRE(q.push(packet('b', 10)));
    REQUIRE(q.push(packet('g', 10), SendQueue::Kind::kept));  // the other laser
    std::vector<int> done;
    q.push_safety(packet('S', 5), [&](bool ok) { done.push_back(ok ? 1 : 0); });
    REQUIRE(q.push(packet('h', 10), SendQueue::Kind::kept));  // after the cease: stays behind
    const auto d = drain(q, 4, done);
    CHECK(order(d.wire) == "fgSabh");
    CHECK(done == std::vector<int>{1});
}

TEST_CASE("send queue: displacement is by bytes as well, and kept packets are never dropped",
          "[send_queue]") {
    SendQueue q(SendQueueLimits{.max_packets = 100, .max_bytes = 30});
    REQUIRE(q.push(packet('a', 10)));
    REQUIRE(q.push(packet('b', 10)));
    REQUIRE(q.push(packet('c', 10)));
    CHECK(q.push_safety(packet('S', 15), nullptr) == 2);  // 'a' and 'b' go
    CHECK(q.bytes() == 25);
    std::vector<int> done;
    CHECK(order(drain(q, 100, done).wire) == "Sc");

    // Nothing displaceable: the safety packet still goes in (never refused).
    REQUIRE(q.push(packet('k', 30), SendQueue::Kind::kept));
    CHECK(q.push_safety(packet('S', 5), nullptr) == 0);
    CHECK(q.bytes() == 35);
    CHECK(order(drain(q, 100, done).wire) == "kS");
}

TEST_CASE("send queue: clear discards everything and hands back the safety handlers",
          "[send_queue]") {
    SendQueue q(SendQueueLimits{});
    REQUIRE(q.push(packet('a', 10)));
    std::vector<int> done;
    q.push_safety(packet('S', 5), [&](bool ok) { done.push_back(ok ? 1 : 0); });
    q.push_safety(packet('T', 5), nullptr);
    CHECK_FALSE(q.written(2).packet_done);  // half of 'S'
    auto handlers = q.clear();
    REQUIRE(handlers.size() == 1);  // 'T' has none
    handlers[0](false);
    CHECK(done == std::vector<int>{0});
    CHECK(q.empty());
    CHECK(q.dropped() == 3);
    CHECK(q.bytes() == 0);
    CHECK_FALSE(q.half_written());
    CHECK(q.next().empty());
}
