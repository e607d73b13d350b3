#include "terrain_loader.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

#include "logging.hpp"

namespace gimbald {

namespace log = gimbal::log;
using gimbal::terrain::Block;

namespace {
constexpr int reader_nice = 10;
}

TerrainLoader::TerrainLoader(boost::asio::io_context& io, gimbal::terrain::ElevationModel& model,
                             TerrainLoaderOptions options)
    : options_(options),
      reader_(model.read_elsewhere(*this)),
      layout_(reader_ ? reader_->layout() : nullptr),
      keep_going_([this] { return !stopping_.load(); }),
      budget_ms_(static_cast<double>(options.wait_budget.count())),
      worker_(io, {"terrain", 4, 1024, 4}) {
    worker_.start();
}

TerrainLoader::~TerrainLoader() {
    stop(std::chrono::milliseconds(0));
    worker_.stop();
}

bool TerrainLoader::stop(std::chrono::milliseconds grace) {
    stopping_ = true;
    std::unique_lock lock(mutex_);
    wanted_.clear();
    read_done_.notify_all();  // lookups waiting for a block
    return read_done_.wait_for(lock, grace, [this] { return !loop_running_; });
}

bool TerrainLoader::fetch(const Key& key, Block& out) {
    if (!reader_) return false;
    bool log_slow = false;
    {
        std::unique_lock lock(mutex_);
        if (take(key, out)) return true;
        want(key, true);
        want_around(key);
        if (!loop_running_ && !wanted_.empty() && !stopping_) {
            loop_running_ = true;
            worker_.submit([this] { read_loop(); });
        }
        const auto now = Clock::now();
        if (waiting_allowed(now)) {
            const auto limit = std::min(
                options_.wait, std::chrono::milliseconds(static_cast<std::int64_t>(budget_ms_)));
            ++counters_.waits;
            read_done_.wait_for(lock, limit, [&] {
                return stopping_ || std::any_of(ready_.begin(), ready_.end(),
                                                [&](const Ready& r) { return r.key == key; });
            });
            budget_ms_ -= std::chrono::duration<double, std::milli>(Clock::now() - now).count();
            if (take(key, out)) return true;
            log_slow = !stalled_;
            stalled_ = true;
        }
        ++counters_.not_ready;
    }
    if (log_slow)
        log::warn("terrain_slow",
                  "a terrain block was not read within the io thread's wait: the ground there is "
                  "unknown until the reads catch up",
                  {{"wait_ms", options_.wait.count()}});
    return false;
}

bool TerrainLoader::waiting_allowed(Clock::time_point now) {
    const double rate = static_cast<double>(options_.wait_budget.count());  // ms per second
    budget_ms_ =
        std::min(rate, budget_ms_ + rate * std::chrono::duration<double>(now - refilled_).count());
    refilled_ = now;
    return !stalled_ && !slow_ && !stopping_ && budget_ms_ >= 1;
}

bool TerrainLoader::take(const Key& key, Block& out) {
    const auto it =
        std::find_if(ready_.begin(), ready_.end(), [&](const Ready& r) { return r.key == key; });
    if (it == ready_.end()) return false;
    out = std::move(it->block);
    ready_.erase(it);
    return true;
}

void TerrainLoader::want(const Key& key, bool asked) {
    if (reading_ && *reading_ == key) return;
    if (std::any_of(ready_.begin(), ready_.end(), [&](const Ready& r) { return r.key == key; }))
        return;
    const auto it = std::find(wanted_.begin(), wanted_.end(), key);
    if (it != wanted_.end()) {
        if (!asked) return;
        wanted_.erase(it);
    }
    // Asked for now: read next. Around it: after everything asked for.
    if (asked)
        wanted_.push_front(key);
    else
        wanted_.push_back(key);
    if (wanted_.size() > options_.max_wanted) {
        wanted_.pop_back();
        ++counters_.dropped;
    }
}

void TerrainLoader::want_around(const Key& key) {
    const auto& lattice = layout_->lattices[key.lattice];
    for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
            const Key around{key.lattice, key.row + dr, key.col + dc};
            if ((dr || dc) && gimbal::terrain::block_in_reach(lattice, around)) want(around, false);
        }
}

void TerrainLoader::read_loop() {
    // Decoding competes for the CPU with the io thread: it yields to it (Linux nice is per
    // thread).
    setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), reader_nice);
    for (;;) {
        Key key;
        {
            std::lock_guard lock(mutex_);
            if (stopping_ || wanted_.empty()) {
                loop_running_ = false;
                read_done_.notify_all();  // stop() waits for this
                return;
            }
            key = wanted_.front();
            wanted_.pop_front();
            reading_ = key;
        }
        Block block;
        const auto started = Clock::now();
        const bool complete = reader_->read(key, block, keep_going_);
        const bool slow = Clock::now() - started > options_.wait;
        {
            std::lock_guard lock(mutex_);
            reading_.reset();
            ++counters_.reads;
            stalled_ = false;
            slow_ = slow;
            if (complete) ready_.push_back({key, std::move(block)});
            if (ready_.size() > options_.max_ready) {
                ready_.pop_front();
                ++counters_.dropped;
            }
        }
        read_done_.notify_all();
    }
}

TerrainLoaderCounters TerrainLoader::counters() const {
    std::lock_guard lock(mutex_);
    return counters_;
}

}  // namespace gimbald
