#include "worker.hpp"

#include <pthread.h>

#include <boost/asio/post.hpp>
#include <utility>

namespace gimbald {

Worker::Worker(boost::asio::io_context& io, WorkerOptions options)
    : io_(io), options_(std::move(options)) {}

Worker::~Worker() {
    stop();
}

void Worker::start() {
    std::lock_guard lock(mutex_);
    if (thread_.joinable() || stopping_) return;
    thread_ = std::thread([this] { run(); });
    const std::string name = options_.name.substr(0, 15);
    if (!name.empty()) pthread_setname_np(thread_.native_handle(), name.c_str());
}

void Worker::stop() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        dropped_jobs_ += queue_.size();
        queue_.clear();
        queued_bytes_ = 0;
    }
    shared_->alive = false;
    wake_.notify_all();
    if (thread_.joinable() && !on_worker_thread()) thread_.join();
}

bool Worker::submit(Job job, std::size_t bytes) {
    bool lost = false;
    {
        std::lock_guard lock(mutex_);
        if (stopping_ || bytes > options_.max_bytes) {
            ++dropped_jobs_;
            return false;
        }
        while (!queue_.empty() &&
               (queue_.size() >= options_.max_jobs || queued_bytes_ + bytes > options_.max_bytes)) {
            queued_bytes_ -= queue_.front().bytes;
            queue_.pop_front();
            ++dropped_jobs_;
            lost = true;
        }
        queue_.push_back({std::move(job), bytes});
        queued_bytes_ += bytes;
        ++jobs_;
    }
    wake_.notify_one();
    return !lost;
}

bool Worker::deliver(std::function<void()> result) {
    auto shared = shared_;
    if (!shared->alive || shared->in_flight.load() >= options_.max_deliveries) {
        ++shared->dropped_deliveries;
        return false;
    }
    ++shared->in_flight;
    boost::asio::post(io_, [shared, result = std::move(result)] {
        --shared->in_flight;
        if (!shared->alive) return;
        ++shared->deliveries;
        result();
    });
    return true;
}

void Worker::run() {
    for (;;) {
        Waiting next;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
            if (stopping_) return;
            next = std::move(queue_.front());
            queue_.pop_front();
            queued_bytes_ -= next.bytes;
        }
        next.job();
        std::lock_guard lock(mutex_);
        ++done_;
    }
}

WorkerCounters Worker::counters() const {
    WorkerCounters c;
    {
        std::lock_guard lock(mutex_);
        c.jobs = jobs_;
        c.dropped_jobs = dropped_jobs_;
        c.done = done_;
        c.queued = queue_.size();
        c.queued_bytes = queued_bytes_;
    }
    c.deliveries = shared_->deliveries;
    c.dropped_deliveries = shared_->dropped_deliveries;
    return c;
}

}  // namespace gimbald
