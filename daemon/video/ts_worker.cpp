#include "video/ts_worker.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <utility>

#include "video/klv_track.hpp"

namespace gimbald::video {

namespace gv = gimbal::video;
namespace klv = gimbal::klv;
using Clock = std::chrono::steady_clock;

namespace {
constexpr int worker_nice = 10;
}  // namespace

TsWorker::TsWorker(boost::asio::io_context& io, TsWorkerOptions options, OnBatch on_batch)
    : options_(std::move(options)),
      on_batch_(std::move(on_batch)),
      demux_({[this](const gv::AccessUnit& au) {
                  if (au.data.size() > gv::max_access_unit_bytes) {
                      std::lock_guard lock(mutex_);
                      ++counters_.dropped_units;
                      return;
                  }
                  batch_.units.emplace_back(au);
              },
              [this](const gv::KlvUnit& unit) {
                  if (!options_.klv) return;
                  const std::size_t taken = batch_.klv.sets.size();
                  klv::CheckLimits limits;
                  limits.max_json_bytes = KlvTrack::max_json_bytes;
                  limits.max_sets = options_.max_klv_sets - std::min(taken, options_.max_klv_sets);
                  klv::CheckedSets found = klv::check_sets(unit.data, limits);
                  batch_.klv.bad_checksums += found.bad_checksums;
                  batch_.klv.refused += found.refused;
                  for (auto& set : found.sets) batch_.klv.sets.push_back(std::move(set));
              },
              {}}),
      worker_(io, WorkerOptions{options_.name, options_.max_datagrams, options_.max_datagram_bytes,
                                options_.max_batches}) {
    worker_.start();
    // Under a flood the io thread (the dead-man, the links, the command path) gets the CPU
    // first: this thread runs at a lower priority. Linux keeps a nice value per thread.
    worker_.submit([] { setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), worker_nice); });
}

TsWorker::~TsWorker() {
    stop();
}

void TsWorker::stop() {
    worker_.stop();
}

void TsWorker::push(std::span<const std::uint8_t> datagram, Clock::time_point arrival) {
    worker_.submit([this, data = std::vector<std::uint8_t>(datagram.begin(), datagram.end()),
                    arrival] { take(data, arrival); },
                   datagram.size());
}

void TsWorker::take(const std::vector<std::uint8_t>& datagram, Clock::time_point arrival) {
    batch_ = TsBatch{};
    batch_.arrival = arrival;
    demux_.push(datagram);
    {
        std::lock_guard lock(mutex_);
        counters_.demux = demux_.stats();
        counters_.klv = demux_.program() ? demux_.program()->klv : std::nullopt;
    }
    if (!batch_.empty()) hand_over(std::move(batch_));
}

void TsWorker::hand_over(TsBatch batch) {
    std::size_t bytes = 0;
    for (const auto& au : batch.units) bytes += au.data.size();
    if (bytes > 0 && shared_->unit_bytes.load() + bytes > options_.max_unit_bytes) {
        // The io thread is behind: this datagram's access units go, its KLV is kept.
        std::lock_guard lock(mutex_);
        counters_.dropped_units += batch.units.size();
        batch.units.clear();
        bytes = 0;
        if (batch.empty()) return;
    }
    shared_->unit_bytes += bytes;
    const std::size_t units = batch.units.size();
    const std::size_t sets = batch.klv.sets.size();
    const bool delivered =
        worker_.deliver([this, shared = shared_, bytes, batch = std::move(batch)]() mutable {
            shared->unit_bytes -= bytes;
            on_batch_(batch);
        });
    if (!delivered) {
        shared_->unit_bytes -= bytes;
        std::lock_guard lock(mutex_);
        counters_.dropped_units += units;
        counters_.dropped_klv_sets += sets;
    }
}

TsWorkerCounters TsWorker::counters() const {
    TsWorkerCounters c;
    {
        std::lock_guard lock(mutex_);
        c = counters_;
    }
    c.dropped_datagrams = worker_.counters().dropped_jobs;
    return c;
}

}  // namespace gimbald::video
