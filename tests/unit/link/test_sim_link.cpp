#include <catch2/catch.hpp>

#include <memory>

#include "link/sim_link.hpp"
#include "link_test_support.hpp"

using namespace link_test;

namespace {

// What the test can still see once the link owns the device.
struct EchoLog {
    std::vector<double> times;  // every now_s the device was given, in call order
    int advances = 0;
    Bytes received;
};

// A real (tiny) device: every byte it receives it sends back on the next advance().
class EchoDevice final : public gimbal::sim::Device {
  public:
    explicit EchoDevice(std::shared_ptr<EchoLog> log) : log_(std::move(log)) {}

    void receive(std::span<const std::uint8_t> bytes, double now_s) override {
        log_->times.push_back(now_s);
        log_->received.insert(log_->received.end(), bytes.begin(), bytes.end());
        pending_.insert(pending_.end(), bytes.begin(), bytes.end());
    }
    void advance(double now_s, std::vector<std::uint8_t>& out) override {
        log_->times.push_back(now_s);
        ++log_->advances;
        out.insert(out.end(), pending_.begin(), pending_.end());
        pending_.clear();
    }

  private:
    std::shared_ptr<EchoLog> log_;
    Bytes pending_;
};

}  // namespace

TEST_CASE("sim link is connected after start and echoes through the device", "[sim]") {
    boost::asio::io_context io;
    auto log = std::make_shared<EchoLog>();
    gimbald::SimLink link(io, std::make_unique<EchoDevice>(log));
    CHECK(link.type() == "sim");
    CHECK(link.endpoint() == "sim");
    CHECK_FALSE(link.connected());
    CHECK_FALSE(link.send({1}));

    LinkEvents events;
    events.start(link);
    CHECK(link.connected());
    CHECK(events.ups == 0);  // reported from the io_context, not from inside start()
    REQUIRE(run_until(io, [&] { return events.ups == 1; }));

    const Bytes packet{0xD0, 0x0D, 0x28, 0x00, 0x0B, 0xCA};
    CHECK(link.send(packet));
    CHECK(log->received == packet);
    REQUIRE(run_until(io, [&] { return events.received.size() >= packet.size(); }));
    CHECK(events.received == packet);
    CHECK(link.stats().tx_bytes == packet.size());
    CHECK(link.stats().tx_packets == 1);
    CHECK(link.stats().rx_bytes == packet.size());
    CHECK(link.stats().last_rx.has_value());
    CHECK(link.stats().tx_dropped == 1);  // the send before start()
}

TEST_CASE("sim link gives the device monotonic time and ticks repeatedly", "[sim]") {
    boost::asio::io_context io;
    auto log = std::make_shared<EchoLog>();
    gimbald::SimLink link(io, std::make_unique<EchoDevice>(log), {.tick_s = 0.002});
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return log->advances >= 5; }));
    link.send_now(Bytes{7});
    REQUIRE(run_until(io, [&] { return log->advances >= 8; }));
    CHECK(events.received == Bytes{7});
    for (std::size_t i = 0; i < log->times.size(); ++i) {
        CHECK(log->times[i] >= 0.0);
        if (i > 0) CHECK(log->times[i] >= log->times[i - 1]);
    }
}

TEST_CASE("sim link stays silent after stop", "[sim]") {
    boost::asio::io_context io;
    auto log = std::make_shared<EchoLog>();
    gimbald::SimLink link(io, std::make_unique<EchoDevice>(log), {.tick_s = 0.002});
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return events.ups == 1 && log->advances >= 2; }));
    CHECK(link.send({1, 2}));
    link.stop();
    CHECK_FALSE(link.connected());
    CHECK_FALSE(link.send({3}));
    const int advances = log->advances;
    run_for(io, 50ms);
    CHECK(log->advances == advances);
    CHECK(events.received.empty());
    CHECK(events.downs == 0);

    // And it can be started again.
    events.start(link);
    REQUIRE(run_until(io, [&] { return events.received == Bytes{1, 2}; }));
}

TEST_CASE("sim link hands a cease-fire to the device at once and reports it written", "[sim]") {
    boost::asio::io_context io;
    auto log = std::make_shared<EchoLog>();
    gimbald::SimLink link(io, std::make_unique<EchoDevice>(log));
    CHECK_FALSE(link.send_safety({1, 2, 3}, [](bool) { FAIL("called while stopped"); }));
    LinkEvents events;
    events.start(link);
    REQUIRE(run_until(io, [&] { return events.ups == 1; }));
    std::vector<bool> outcomes;
    REQUIRE(link.send_safety({9, 8, 7}, [&](bool ok) { outcomes.push_back(ok); }));
    CHECK(outcomes.empty());  // never from inside the call
    CHECK(log->received == Bytes{9, 8, 7});
    REQUIRE(run_until(io, [&] { return outcomes.size() == 1; }));
    CHECK(outcomes[0]);
    CHECK(link.send_kept({4}));
    CHECK(link.send_now(std::vector<std::uint8_t>{5}));
    link.stop();
    CHECK_FALSE(link.send_now(std::vector<std::uint8_t>{6}));
    CHECK(log->received == Bytes{9, 8, 7, 4, 5});
}
