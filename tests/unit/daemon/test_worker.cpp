// The worker thread that keeps untrusted work off the io thread (contract section 14 v4):
// jobs run in order off the io thread, results come back on it, a flood drops the oldest
// waiting jobs (counted) instead of growing, and nothing runs after stop().
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <functional>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "worker.hpp"

using gimbald::Worker;
using gimbald::WorkerOptions;

namespace {

// Runs the io_context until `done` or two seconds passed.
void run_until(boost::asio::io_context& io, const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (!done() && std::chrono::steady_clock::now() < deadline) {
        io.restart();
        io.run_for(std::chrono::milliseconds(5));
    }
}

}  // namespace

TEST_CASE("Worker: jobs run off the io thread, in order; results run on it", "[worker]") {
    boost::asio::io_context io;
    Worker worker(io, {"test", 16, 1024, 16});
    worker.start();
    const auto io_thread = std::this_thread::get_id();
    std::vector<int> results;
    std::atomic<bool> job_on_io{false};
    for (int i = 0; i < 10; ++i)
        REQUIRE(worker.submit([&, i] {
            if (std::this_thread::get_id() == io_thread) job_on_io = true;
            worker.deliver([&, i] {
                CHECK(std::this_thread::get_id() == io_thread);
                results.push_back(i);
            });
        }));
    run_until(io, [&] { return results.size() == 10; });
    CHECK_FALSE(job_on_io);
    CHECK(results == std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
    const auto c = worker.counters();
    CHECK(c.jobs == 10);
    CHECK(c.done == 10);
    CHECK(c.deliveries == 10);
    CHECK(c.dropped_jobs == 0);
}

TEST_CASE("Worker: a flood drops the oldest waiting jobs, by count and by bytes", "[worker]") {
    boost::asio::io_context io;
    Worker worker(io, {"test", 4, 100, 16});
    worker.start();
    // Hold the thread in a first job so the others wait.
    std::promise<void> release;
    auto released = release.get_future().share();
    std::atomic<bool> holding{false};
    REQUIRE(worker.submit([&, released] {
        holding = true;
        released.wait();
    }));
    while (!holding) std::this_thread::yield();

    std::vector<int> ran;
    std::mutex ran_mutex;
    auto job = [&](int i) {
        return [&, i] {
            std::lock_guard lock(ran_mutex);
            ran.push_back(i);
        };
    };
    for (int i = 0; i < 4; ++i) CHECK(worker.submit(job(i), 10));
    CHECK_FALSE(worker.submit(job(4), 10));   // by count: 0 dropped
    CHECK_FALSE(worker.submit(job(5), 80));   // count, then bytes: 1 and 2 dropped
    CHECK_FALSE(worker.submit(job(6), 101));  // larger than the whole budget: refused
    CHECK(worker.counters().dropped_jobs == 4);
    CHECK(worker.counters().queued == 3);
    CHECK(worker.counters().queued_bytes == 100);
    release.set_value();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (worker.counters().done < 4 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::lock_guard lock(ran_mutex);
    CHECK(ran == std::vector<int>{3, 4, 5});
}

TEST_CASE("Worker: results beyond max_deliveries are dropped and counted", "[worker]") {
    boost::asio::io_context io;
    Worker worker(io, {"test", 16, 1024, 3});
    worker.start();
    std::atomic<int> accepted{0};
    REQUIRE(worker.submit([&] {
        for (int i = 0; i < 10; ++i)
            if (worker.deliver([] {})) ++accepted;
    }));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (worker.counters().done < 1 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    CHECK(accepted == 3);  // the io thread did not run in between
    CHECK(worker.counters().dropped_deliveries == 7);
    run_until(io, [&] { return worker.counters().deliveries == 3; });
    CHECK(worker.counters().deliveries == 3);
}

TEST_CASE("Worker: nothing runs after stop()", "[worker]") {
    boost::asio::io_context io;
    bool delivered = false;
    {
        Worker worker(io, {"test", 16, 1024, 16});
        worker.start();
        std::atomic<bool> posted{false};
        REQUIRE(worker.submit([&] {
            worker.deliver([&] { delivered = true; });
            posted = true;
        }));
        while (!posted) std::this_thread::yield();
        worker.stop();
        CHECK_FALSE(worker.submit([] {}));
    }
    io.run();  // the posted result finds its worker gone
    CHECK_FALSE(delivered);
}
