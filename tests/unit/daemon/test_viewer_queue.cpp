// A video viewer's queue (contract section 18): the configuration before the first key frame
// and when it changes; nothing before a key frame; a backlog dropped up to the next key
// frame, the message being written kept.
#include <catch2/catch.hpp>
#include <memory>
#include <string>
#include <vector>

#include "http/viewer_queue.hpp"

using gimbald::http::VideoMessage;
using gimbald::http::ViewerQueue;
using Offer = ViewerQueue::Offer;

namespace {

VideoMessage msg(const std::string& s) {
    return std::make_shared<const std::string>(s);
}

// Everything queued, written out: the messages' texts in order.
std::vector<std::string> drain(ViewerQueue& q) {
    std::vector<std::string> out;
    while (!q.empty()) {
        q.start_write();
        out.push_back(*q.front().bytes);
        q.written();
    }
    return out;
}

}  // namespace

TEST_CASE("Viewer queue: configuration, then a key frame first", "[http][video]") {
    ViewerQueue q(15);
    const auto config = msg("config");
    CHECK(q.offer(nullptr, msg("K0"), true) == Offer::skipped);  // no configuration yet
    CHECK(q.offer(config, msg("P1"), false) == Offer::skipped);  // not a key frame
    CHECK(q.empty());
    CHECK(q.offer(config, msg("K2"), true) == Offer::queued);
    CHECK(q.front().text);
    CHECK(q.offer(config, msg("P3"), false) == Offer::queued);
    CHECK(q.offer(config, msg("K4"), true) == Offer::queued);  // same configuration: not again
    CHECK(drain(q) == std::vector<std::string>{"config", "K2", "P3", "K4"});
    const auto changed = msg("config 2");
    CHECK(q.offer(changed, msg("P5"), false) == Offer::queued);  // takes effect at a key frame
    CHECK(q.offer(changed, msg("K6"), true) == Offer::queued);
    CHECK(drain(q) == std::vector<std::string>{"P5", "config 2", "K6"});
}

TEST_CASE("Viewer queue: a backlog is dropped up to the next key frame", "[http][video]") {
    ViewerQueue q(3);
    const auto config = msg("config");
    REQUIRE(q.offer(config, msg("K0"), true) == Offer::queued);
    q.start_write();  // "config" is being written and never finishes
    CHECK(q.offer(config, msg("P1"), false) == Offer::queued);
    CHECK(q.offer(config, msg("P2"), false) == Offer::queued);  // 3 wait behind the write
    CHECK(q.offer(config, msg("P3"), false) == Offer::backlog_dropped);
    CHECK(q.size() == 1);  // only the message in flight
    CHECK(q.offer(config, msg("P4"), false) == Offer::skipped);
    CHECK(q.offer(config, msg("K5"), true) == Offer::queued);
    CHECK(q.offer(config, msg("P6"), false) == Offer::queued);
    q.written();
    CHECK(drain(q) == std::vector<std::string>{"K5", "P6"});

    // A key frame arriving on a full backlog replaces it at once.
    REQUIRE(q.offer(config, msg("P7"), false) == Offer::queued);
    q.start_write();
    q.offer(config, msg("P8"), false);
    q.offer(config, msg("P9"), false);
    q.offer(config, msg("P10"), false);
    CHECK(q.offer(config, msg("K11"), true) == Offer::backlog_dropped);
    q.written();
    CHECK(drain(q) == std::vector<std::string>{"K11"});
}
