// A thread of its own for work that must never run on the io thread (contract section 14 v4):
// expanding untrusted bytes (TS/PES reassembly, KLV decoding), GDAL reads, rendering. The io
// thread times the laser dead-man; it only hands jobs over and takes small, typed results
// back, so no input - of any size or shape - can make a cease-fire wait.
//
// Jobs wait in a bounded queue (a count and a byte budget); when a new job does not fit, the
// oldest waiting jobs are dropped and counted, so a flood costs the flood itself, never
// memory or the io thread's time. A job hands its result to the io thread with deliver(),
// bounded the same way (at most max_deliveries waiting there; more are dropped and counted).
// Nothing delivered runs after stop() or the worker's destruction.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <boost/asio/io_context.hpp>

namespace gimbald {

struct WorkerOptions {
    std::string name;                         // the thread's name (at most 15 characters shown)
    std::size_t max_jobs = 64;                // waiting jobs
    std::size_t max_bytes = 8 * 1024 * 1024;  // the waiting jobs' declared sizes together
    std::size_t max_deliveries = 256;         // results waiting on the io thread
};

struct WorkerCounters {
    std::uint64_t jobs = 0;                // accepted by submit()
    std::uint64_t dropped_jobs = 0;        // waiting jobs dropped to make room, or refused
    std::uint64_t done = 0;                // jobs that ran
    std::uint64_t deliveries = 0;          // results that ran on the io thread
    std::uint64_t dropped_deliveries = 0;  // results dropped: too many waiting on the io thread
    std::size_t queued = 0;                // jobs waiting now
    std::size_t queued_bytes = 0;
};

class Worker {
  public:
    using Job = std::function<void()>;

    Worker(boost::asio::io_context& io, WorkerOptions options);
    ~Worker();
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;

    // Starts the thread (once; submit() before start() only queues).
    void start();
    // Drops the waiting jobs, lets the running one finish, joins the thread. After it returns
    // no job runs and no delivered result runs on the io thread. Idempotent.
    void stop();

    // From any thread: queue `job`, declaring `bytes` of input it holds. When it does not fit
    // (max_jobs, max_bytes), the oldest waiting jobs are dropped (counted) until it does; a
    // job larger than max_bytes by itself is refused (counted). Returns false when anything
    // was dropped or refused. After stop(): refused.
    bool submit(Job job, std::size_t bytes = 0);

    // From a job: run `result` on the io thread. Returns false (and counts it) when
    // max_deliveries results already wait there or the worker is stopping.
    bool deliver(std::function<void()> result);

    WorkerCounters counters() const;
    bool on_worker_thread() const { return std::this_thread::get_id() == thread_.get_id(); }

  private:
    struct Waiting {
        Job job;
        std::size_t bytes = 0;
    };
    // What the io side's posted handlers see: alive until stop().
    struct Shared {
        std::atomic<bool> alive{true};
        std::atomic<std::size_t> in_flight{0};
        std::atomic<std::uint64_t> deliveries{0};
        std::atomic<std::uint64_t> dropped_deliveries{0};
    };

    void run();

    boost::asio::io_context& io_;
    WorkerOptions options_;
    std::shared_ptr<Shared> shared_ = std::make_shared<Shared>();
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<Waiting> queue_;
    std::size_t queued_bytes_ = 0;
    bool stopping_ = false;
    std::uint64_t jobs_ = 0;
    std::uint64_t dropped_jobs_ = 0;
    std::uint64_t done_ = 0;
    std::thread thread_;
};

}  // namespace gimbald
