#include "record/recorder.hpp"

#include <chrono>
#include <cmath>
#include <csignal>
#include <stdexcept>
#include <utility>

namespace gimbald::record {

namespace log = gimbal::log;

namespace {

std::int64_t unix_seconds_now() {
    return std::chrono::duration_cast<std::chrono::seconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

std::uint64_t megabytes(double mb) {
    return static_cast<std::uint64_t>(std::llround(mb * 1000.0 * 1000.0));
}

// The writer wakes at least this often, and at once when the buffer is a quarter full.
constexpr auto writer_period = std::chrono::milliseconds(200);
constexpr auto sync_period = std::chrono::seconds(1);

}  // namespace

Recorder::Recorder(boost::asio::io_context& io, RecorderOptions options)
    : options_(std::move(options)),
      files_(RecordFilesOptions{
          options_.dir, megabytes(options_.max_file_mb), megabytes(options_.max_total_mb),
          gimbal::record::file_header(options_.user_application, options_.interfaces)}),
      report_timer_(io),
      buffer_full_log_(log::Level::warn, "record_dropped", "packets not recorded"),
      write_error_log_(log::Level::error, "record_write_error", "packets lost to write errors") {
    // A file-size limit (ulimit -f) must be a write error (EFBIG), handled like a full disk,
    // not the default SIGXFSZ that would kill the daemon.
    std::signal(SIGXFSZ, SIG_IGN);
    if (auto error = files_.open_first(unix_seconds_now()); !error.empty())
        throw std::runtime_error("record: cannot create a recording file: " + error);
    file_ = files_.current_path();
    reported_file_ = file_;
    files_.take_opened();  // the first file is logged here
    file_bytes_ = files_.current_bytes();
    buffer_.reserve(options_.buffer_bytes);
    log::info("record_file", "recording to a new file",
              {{"file", file_}, {"interfaces", options_.interfaces.size()}});
    writer_ = std::thread([this] { writer_loop(); });
    schedule_report();
}

Recorder::~Recorder() {
    stop();
}

void Recorder::record(std::uint32_t interface_id, Direction direction, std::string_view dissector,
                      std::span<const std::uint8_t> pdu) {
    if (stopped_) return;
    const auto now_us = std::chrono::duration_cast<std::chrono::microseconds>(
                            std::chrono::system_clock::now().time_since_epoch())
                            .count();
    const std::size_t size = gimbal::record::packet_block_size(dissector, pdu.size());
    bool wake = false;
    bool full = false;
    {
        const std::lock_guard lock(mutex_);
        if (buffer_.size() + size > options_.buffer_bytes) {
            full = true;
            ++buffer_full_;
            dropped_.fetch_add(1, std::memory_order_relaxed);
        } else {
            gimbal::record::append_packet(
                buffer_,
                {interface_id, static_cast<std::uint64_t>(now_us), direction, dissector, pdu});
            wake = buffer_.size() >= options_.buffer_bytes / 4;
        }
    }
    if (full)  // dropped: the buffer is full (the disk is slower than the links)
        buffer_full_log_.hit("recording buffer full: packet not recorded",
                             {{"total", buffer_full_}});
    if (wake) wake_.notify_one();
}

void Recorder::writer_loop() {
    std::vector<std::uint8_t> chunk;
    chunk.reserve(options_.buffer_bytes);
    auto last_sync = std::chrono::steady_clock::now();
    for (;;) {
        bool stopping = false;
        {
            std::unique_lock lock(mutex_);
            wake_.wait_for(lock, writer_period, [this] {
                return stopping_ || buffer_.size() >= options_.buffer_bytes / 4;
            });
            chunk.swap(buffer_);
            stopping = stopping_;
        }
        if (!chunk.empty()) {
            const auto lost = files_.write(chunk, unix_seconds_now());
            chunk.clear();
            if (lost) {
                dropped_.fetch_add(lost, std::memory_order_relaxed);
                write_failures_.fetch_add(lost, std::memory_order_relaxed);
            }
            {
                const std::lock_guard lock(file_mutex_);
                file_ = files_.current_path();
                for (auto& path : files_.take_opened()) opened_.push_back(std::move(path));
                if (auto error = files_.take_error(); !error.empty()) last_error_ = error;
            }
            file_bytes_.store(files_.current_bytes(), std::memory_order_relaxed);
        }
        // Power loss: at most about a second of recording is lost once written.
        const auto now = std::chrono::steady_clock::now();
        if (stopping || now - last_sync >= sync_period) {
            files_.sync();
            last_sync = now;
        }
        if (stopping) break;
    }
    files_.close();
}

void Recorder::stop() {
    if (stopped_) return;
    stopped_ = true;
    report_timer_.cancel();
    {
        const std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_one();
    if (writer_.joinable()) writer_.join();
    report();
    log::info("record_closed", "recording closed",
              {{"file", reported_file_}, {"dropped", dropped()}});
}

void Recorder::schedule_report() {
    report_timer_.expires_after(std::chrono::seconds(1));
    report_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopped_) return;
        report();
        schedule_report();
    });
}

// Logs from the io thread what the writer thread saw (the logger is not shared with it).
void Recorder::report() {
    std::string error;
    std::vector<std::string> opened;
    {
        const std::lock_guard lock(file_mutex_);
        error = std::exchange(last_error_, std::string());
        opened.swap(opened_);
    }
    for (auto& file : opened) {  // every rotation, also several within one second
        log::info("record_file", "recording to a new file",
                  {{"file", file}, {"previous", reported_file_}});
        reported_file_ = std::move(file);
    }
    const auto failures = write_failures_.load(std::memory_order_relaxed);
    if (failures > reported_failures_ || !error.empty()) {
        write_error_log_.hit("cannot write the recording (packets dropped, still running)",
                             {{"error", error}, {"total", failures}});
        reported_failures_ = failures;
    }
    write_error_log_.poll();
    buffer_full_log_.poll();
}

nlohmann::json Recorder::snapshot() const {
    std::string file;
    {
        const std::lock_guard lock(file_mutex_);
        file = file_;
    }
    return {{"file", file},
            {"bytes", file_bytes_.load(std::memory_order_relaxed)},
            {"dropped", dropped()}};
}

}  // namespace gimbald::record
