// The work on a UDP video input's bytes, off the io thread (contract section 14 v4). The io
// thread receives each datagram and hands it over (push); on a gimbald::Worker thread it is
// demultiplexed (lib/video TsDemuxer) and the KLV units it completes are checked and decoded
// (klv::check_sets: size, checksum, item count first; each set's JSON cut to 8 KiB). What one
// datagram gives - its access units, checked KLV sets and their counts - goes back to the io
// thread as one TsBatch (on_batch runs there).
//
// Bounded everywhere, so a flood costs the flood itself and never the dead-man's time:
// datagrams waiting for the worker (count and bytes; the oldest dropped), batches waiting on
// the io thread (count), the access units' bytes waiting there together (past it a datagram's
// units are dropped, its KLV kept), the good sets taken from one datagram, and every buffer
// inside the demuxer. Everything dropped is counted (counters()). The thread runs at a lower
// CPU priority (nice 10) than the io thread, so a flood cannot take the io thread's CPU either.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "klv/checked_sets.hpp"
#include "video/codec.hpp"
#include "video/ts_demuxer.hpp"
#include "worker.hpp"

namespace gimbald::video {

struct TsBatch {
    std::chrono::steady_clock::time_point arrival;  // of the datagram, on the io thread
    std::vector<gimbal::video::AccessUnitBuffer> units;
    gimbal::klv::CheckedSets klv;
    bool empty() const {
        return units.empty() && klv.sets.empty() && klv.bad_checksums == 0 && klv.refused == 0;
    }
};

struct TsWorkerOptions {
    std::string name = "video";  // the thread's name
    bool klv = true;             // check and decode KLV (false: KLV units are ignored)
    std::size_t max_datagrams = 1024;
    std::size_t max_datagram_bytes = 4u << 20;
    std::size_t max_batches = 64;            // waiting on the io thread
    std::size_t max_unit_bytes = 12u << 20;  // access units waiting on the io thread together
    std::size_t max_klv_sets = 64;           // good sets taken from one datagram
};

struct TsWorkerCounters {
    gimbal::video::DemuxStats demux;
    std::optional<gimbal::video::KlvCarriage> klv;  // the stream carries KLV
    std::uint64_t dropped_datagrams = 0;  // waited too long for the worker: dropped, oldest first
    std::uint64_t dropped_units = 0;      // over max_access_unit_bytes, or the io thread behind
    std::uint64_t dropped_klv_sets = 0;   // good sets lost because the io thread was behind
};

class TsWorker {
  public:
    using OnBatch = std::function<void(TsBatch&)>;

    // Starts the thread. on_batch runs on the io thread, never after stop().
    TsWorker(boost::asio::io_context& io, TsWorkerOptions options, OnBatch on_batch);
    ~TsWorker();
    TsWorker(const TsWorker&) = delete;
    TsWorker& operator=(const TsWorker&) = delete;

    // io thread: one datagram (copied). Never blocks.
    void push(std::span<const std::uint8_t> datagram,
              std::chrono::steady_clock::time_point arrival);
    // Joins the thread (the datagram in hand is finished, the waiting ones dropped).
    void stop();

    TsWorkerCounters counters() const;

  private:
    struct Shared {
        std::atomic<std::size_t> unit_bytes{0};  // access units delivered, not yet handled
    };

    // Worker thread only.
    void take(const std::vector<std::uint8_t>& datagram,
              std::chrono::steady_clock::time_point arrival);
    void hand_over(TsBatch batch);

    TsWorkerOptions options_;
    OnBatch on_batch_;
    std::shared_ptr<Shared> shared_ = std::make_shared<Shared>();
    gimbal::video::TsDemuxer demux_;  // worker thread only
    TsBatch batch_;                   // worker thread only: what the current datagram gave
    mutable std::mutex mutex_;
    TsWorkerCounters counters_;  // under mutex_ (dropped_datagrams from the worker)
    Worker worker_;              // last: its thread stops before the members above go
};

}  // namespace gimbald::video
