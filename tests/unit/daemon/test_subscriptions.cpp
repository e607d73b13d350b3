// The subscriber table of the command socket, with time passed in.
#include <catch2/catch.hpp>

#include "subscriptions.hpp"

using boost::asio::ip::make_address;
using gimbald::Subscription;
using gimbald::Subscriptions;
using Endpoint = boost::asio::ip::udp::endpoint;

namespace {
Subscription sub(double rate_hz, double ttl_s, bool events = true) {
    Subscription s;
    s.rate_hz = rate_hz;
    s.ttl_s = ttl_s;
    s.events = events;
    return s;
}
const Endpoint a(make_address("127.0.0.1"), 5000);
const Endpoint b(make_address("127.0.0.1"), 5001);
const Endpoint c(make_address("::1"), 5002);
}  // namespace

TEST_CASE("subscribe adds, renews and refuses beyond max_subscribers", "[subscriptions]") {
    Subscriptions subs(2);
    CHECK(subs.subscribe(a, sub(10, 60), 0.0) == Subscriptions::Result::added);
    CHECK(subs.subscribe(a, sub(5, 60), 1.0) == Subscriptions::Result::renewed);
    CHECK(subs.subscribe(b, sub(10, 60), 1.0) == Subscriptions::Result::added);
    CHECK(subs.subscribe(c, sub(10, 60), 1.0) == Subscriptions::Result::full);
    CHECK(subs.size() == 2);
    CHECK(subs.unsubscribe(a));
    CHECK_FALSE(subs.unsubscribe(a));
    CHECK(subs.subscribe(c, sub(10, 60), 2.0) == Subscriptions::Result::added);
}

TEST_CASE("a subscription ends ttl_s after its last renewal", "[subscriptions]") {
    Subscriptions subs(4);
    subs.subscribe(a, sub(10, 2), 0.0);
    subs.subscribe(a, sub(10, 2), 1.5);  // renewed: now ends at 3.5
    CHECK(subs.expire(3.0).empty());
    const auto gone = subs.expire(3.5);
    REQUIRE(gone.size() == 1);
    CHECK(gone[0] == a);
    CHECK(subs.size() == 0);
    CHECK_FALSE(subs.next_due());
}

TEST_CASE("STATE goes out at once, then at rate_hz on a shared cadence", "[subscriptions]") {
    Subscriptions subs(4);
    subs.subscribe(a, sub(10, 60), 0.013);
    subs.subscribe(b, sub(10, 60), 0.057);
    CHECK(subs.due_state("g", 0.057).size() == 2);  // the first STATE of each, at once
    subs.mark_sent(0.057);
    CHECK(subs.due_state("g", 0.09).empty());
    // Both fall due at the next multiple of the period, so one snapshot serves both.
    CHECK(*subs.next_due() == Approx(0.1));
    CHECK(subs.due_state("g", 0.1).size() == 2);
    subs.mark_sent(0.1);
    // After a stall the missed datagrams are skipped, not sent as a burst.
    subs.mark_sent(0.75);
    CHECK(subs.due_state("g", 0.75).empty());
    CHECK(*subs.next_due() == Approx(0.8));
}

TEST_CASE("gimbal filters and events", "[subscriptions]") {
    Subscriptions subs(4);
    Subscription only_nose = sub(10, 60);
    only_nose.gimbal = "nose";
    subs.subscribe(a, only_nose, 0.0);
    subs.subscribe(b, sub(10, 60, false), 0.0);
    CHECK(subs.due_state("main", 0.0) == std::vector<Endpoint>{b});
    CHECK(subs.due_state("nose", 0.0).size() == 2);
    CHECK(subs.event_targets("nose") == std::vector<Endpoint>{a});
    CHECK(subs.event_targets("main").empty());
}

TEST_CASE("one host holds at most max_per_host subscriptions; others still subscribe",
          "[subscriptions]") {
    Subscriptions subs(64, 3);
    for (unsigned short port = 6000; port < 6003; ++port)
        CHECK(subs.subscribe(Endpoint(make_address("127.0.0.1"), port), sub(10, 60), 0.0) ==
              Subscriptions::Result::added);
    const Endpoint fourth(make_address("127.0.0.1"), 6003);
    CHECK(subs.subscribe(fourth, sub(10, 60), 0.0) == Subscriptions::Result::host_full);
    // A renewal of a subscription the host holds is never refused.
    CHECK(subs.subscribe(Endpoint(make_address("127.0.0.1"), 6001), sub(5, 60), 1.0) ==
          Subscriptions::Result::renewed);
    CHECK(subs.subscribe(Endpoint(make_address("127.0.0.2"), 6003), sub(10, 60), 1.0) ==
          Subscriptions::Result::added);
    CHECK(subs.subscribe(c, sub(10, 60), 1.0) == Subscriptions::Result::added);
    CHECK(subs.size() == 5);
    CHECK(subs.per_host_capacity() == 3);
    // A slot the host gives up is its own again.
    CHECK(subs.unsubscribe(Endpoint(make_address("127.0.0.1"), 6000)));
    CHECK(subs.subscribe(fourth, sub(10, 60), 2.0) == Subscriptions::Result::added);
}

TEST_CASE("a renewal restarts a delta stream with a full STATE", "[subscriptions]") {
    Subscriptions subs(4);
    Subscription s = sub(10, 60);
    s.stream.changes = true;
    subs.subscribe(a, s, 0.0);
    auto* held = subs.find(a);
    REQUIRE(held != nullptr);
    held->cursors["g"].pushed(std::make_shared<const nlohmann::json>(nlohmann::json::object()),
                              true, 0.0, 10.0);
    CHECK_FALSE(subs.find(a)->cursors.at("g").full_due(1.0));
    subs.subscribe(a, s, 1.0);
    CHECK(subs.find(a)->cursors.empty());
}
