// The flight recorder (contract section 12, docs/recording.md): every tapped packet becomes a
// pcapng Enhanced Packet Block appended to a bounded in-memory buffer on the io thread; one
// writer thread moves the buffer to disk in large chunks.
//
// Why a thread: a write() or fdatasync() on a slow or full disk (an SD card on a companion
// computer can stall for seconds) must never stall the io_context that serves the gimbal
// links. Asio 1.74 has no portable asynchronous file I/O, so one plain thread owns the files.
// The io thread only appends to a buffer under a mutex (held for one memcpy-sized encode);
// the writer swaps the buffer out under the same mutex and writes without it. When the buffer
// is full the packet is dropped and counted - a link is never slowed down by the recorder.
#pragma once

#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "logging.hpp"
#include "record/pcapng_writer.hpp"
#include "record/record_config.hpp"
#include "record/record_files.hpp"

namespace gimbald::record {

using gimbal::record::Direction;

// The `record` section (record_config.hpp) and what the daemon adds.
struct RecorderOptions : gimbal::daemon::RecordConfig {
    explicit RecorderOptions(gimbal::daemon::RecordConfig config = {})
        : RecordConfig(std::move(config)) {}
    std::size_t buffer_bytes = 8 * 1024 * 1024;  // about 8 s of 10,000 packets/s
    std::string user_application = "gimbald";
    std::vector<gimbal::record::Interface> interfaces;
};

class Recorder {
  public:
    // Opens the first file; throws std::runtime_error("<path>: <reason>") when it cannot.
    Recorder(boost::asio::io_context& io, RecorderOptions options);
    ~Recorder();
    Recorder(const Recorder&) = delete;
    Recorder& operator=(const Recorder&) = delete;

    // io thread: one packet, stamped now (system clock, microseconds). Never blocks on I/O.
    void record(std::uint32_t interface_id, Direction direction, std::string_view dissector,
                std::span<const std::uint8_t> pdu);
    void record(std::uint32_t interface_id, Direction direction, std::string_view dissector,
                std::string_view text) {
        record(interface_id, direction, dissector,
               {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
    }

    // Flushes everything buffered, fdatasyncs and closes the file, joins the writer (SIGTERM).
    void stop();

    // STATE `record`: {"file", "bytes", "dropped"}.
    nlohmann::json snapshot() const;
    std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

  private:
    void writer_loop();
    void schedule_report();
    void report();

    RecorderOptions options_;
    RecordFiles files_;
    boost::asio::steady_timer report_timer_;

    std::mutex mutex_;
    std::condition_variable wake_;
    std::vector<std::uint8_t> buffer_;  // filled by the io thread, guarded by mutex_
    bool stopping_ = false;             // guarded by mutex_
    std::thread writer_;
    bool stopped_ = false;  // io thread

    // Written by the writer, read by the io thread (STATE, logs).
    std::atomic<std::uint64_t> dropped_{0};         // buffer full + write errors
    std::atomic<std::uint64_t> write_failures_{0};  // packets lost to write errors
    std::atomic<std::uint64_t> file_bytes_{0};
    mutable std::mutex file_mutex_;
    std::string file_;                 // guarded by file_mutex_
    std::string last_error_;           // guarded by file_mutex_
    std::vector<std::string> opened_;  // guarded by file_mutex_: files started, not logged yet

    std::uint64_t buffer_full_ = 0;  // io thread
    std::uint64_t reported_failures_ = 0;
    std::string reported_file_;  // io thread: the last file logged
    gimbal::log::RateLimitedLog buffer_full_log_;
    gimbal::log::RateLimitedLog write_error_log_;
};

}  // namespace gimbald::record
