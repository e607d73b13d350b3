// gimbald's terrain reads, off the io thread (contract section 14 v4; docs/terrain.md "Reads
// off the io thread"). The elevation model lives on the io thread with its block cache; for
// a block it does not hold it asks this loader, whose own thread (a gimbald::Worker) is the
// only one that reads the files through GDAL. A lookup whose block is not read yet waits
// for it at most `wait` - a block of a local file takes about a millisecond, so the first
// telemetry packet and the first `elevation` find their blocks - and all waits together at
// most `wait_budget` per second; while reads take longer than that (a slow disk, a heavy
// file: a wait ran out, or the last read took longer than `wait`), lookups do not wait at
// all. A lookup that goes without its block sees unknown
// ground there for that computation: STATE's footprint and ground fall back to the flat
// world for that packet, and a request gets `unavailable` ("still loading", see
// GroundCommands). The blocks around each block asked for are read after it, so a moving
// footprint finds its next blocks read.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "terrain/block_source.hpp"
#include "terrain/elevation_model.hpp"
#include "worker.hpp"

namespace gimbald {

struct TerrainLoaderOptions {
    std::chrono::milliseconds wait{40};         // the longest one lookup waits for its block
    std::chrono::milliseconds wait_budget{40};  // all waits together, refilled each second
    std::size_t max_wanted = 64;  // blocks waiting to be read; past it the oldest are dropped
    std::size_t max_ready = 64;   // blocks read and not yet asked for (read ahead)
};

struct TerrainLoaderCounters {
    std::uint64_t reads = 0;      // blocks read by the loader thread
    std::uint64_t waits = 0;      // lookups that waited for their block
    std::uint64_t not_ready = 0;  // lookups answered without their block
    std::uint64_t dropped = 0;    // blocks dropped unread (queue full) or unused (read ahead)
};

class TerrainLoader final : public gimbal::terrain::BlockSource {
  public:
    // Takes `model`'s file reader (ElevationModel::read_elsewhere): from now on only the
    // loader thread touches GDAL. `model` must not look a block up after the loader is gone.
    TerrainLoader(boost::asio::io_context& io, gimbal::terrain::ElevationModel& model,
                  TerrainLoaderOptions options = {});
    // Stops the thread (stop(), then waits for a read under way to end).
    ~TerrainLoader() override;
    TerrainLoader(const TerrainLoader&) = delete;
    TerrainLoader& operator=(const TerrainLoader&) = delete;

    // The io thread (the model's cache): the block if it is read, else false (after waiting
    // within the bounds above).
    bool fetch(const gimbal::terrain::BlockKey& key, gimbal::terrain::Block& out) override;

    TerrainLoaderCounters counters() const;

    // Reads nothing more: drops the blocks still wanted, asks the read under way to stop at
    // GDAL's next step and waits up to `grace` for it. False when it is still running: GDAL
    // cannot interrupt every read (3.6 reads a VRT's sources without asking the progress
    // callback), and a daemon told to stop must not wait seconds for one (App).
    bool stop(std::chrono::milliseconds grace);

  private:
    using Clock = std::chrono::steady_clock;
    using Key = gimbal::terrain::BlockKey;
    struct Ready {
        Key key;
        gimbal::terrain::Block block;
    };

    bool take(const Key& key, gimbal::terrain::Block& out);  // under mutex_
    void want(const Key& key, bool asked);                   // under mutex_
    void want_around(const Key& key);                        // under mutex_
    bool waiting_allowed(Clock::time_point now);             // under mutex_
    void read_loop();                                        // the loader thread

    TerrainLoaderOptions options_;
    std::unique_ptr<gimbal::terrain::DemReader> reader_;
    std::shared_ptr<const gimbal::terrain::DemLayout> layout_;
    std::function<bool()> keep_going_;
    std::atomic<bool> stopping_{false};

    mutable std::mutex mutex_;
    std::condition_variable read_done_;
    std::deque<Key> wanted_;      // front: read next
    std::optional<Key> reading_;  // the block being read now
    std::deque<Ready> ready_;     // oldest first
    bool loop_running_ = false;
    bool stalled_ = false;  // a wait ran out and no read finished since
    bool slow_ = false;     // the last read took longer than a wait: waiting would not help
    double budget_ms_;
    Clock::time_point refilled_ = Clock::now();
    TerrainLoaderCounters counters_;

    Worker worker_;  // last: stopped (in the destructor) before the members above go
};

}  // namespace gimbald
