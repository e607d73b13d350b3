// The recording's files on disk (docs/recording.md), used by the recorder's writer thread
// only: names sortable by time, rotation at max_file_bytes (every file starts with the SHB
// and all IDBs), the oldest files deleted past max_total_bytes, fdatasync on request.
// A chunk is written whole blocks at a time; on a nearly full disk what fits is kept - every
// whole block that was written - and the block the write stopped inside is cut off, so the
// file stays readable (contract section 14); the packets that did not fit count as dropped.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace gimbald::record {

struct RecordFilesOptions {
    std::filesystem::path dir;
    std::uint64_t max_file_bytes = 100ull * 1000 * 1000;
    std::uint64_t max_total_bytes = 2000ull * 1000 * 1000;
    std::vector<std::uint8_t> header;  // SHB + IDBs, first bytes of every file
};

// "gimbald-20261125T120000Z-0001.pcapng": UTC start time, then a per-process sequence.
std::string recording_file_name(std::int64_t unix_seconds, unsigned sequence);
// True for names recording_file_name() makes (the only files rotation deletes).
bool is_recording_file_name(std::string_view name);

class RecordFiles {
  public:
    explicit RecordFiles(RecordFilesOptions options);
    ~RecordFiles();
    RecordFiles(const RecordFiles&) = delete;
    RecordFiles& operator=(const RecordFiles&) = delete;

    // Opens the first file. Returns an error text ("<path>: <reason>"), empty on success.
    std::string open_first(std::int64_t unix_seconds);
    // Writes the whole pcapng blocks in `blocks`, rotating between blocks. Returns how many
    // packet blocks could not be written (write or open errors).
    std::uint64_t write(std::span<const std::uint8_t> blocks, std::int64_t unix_seconds);
    void sync();
    void close();

    const std::string& current_path() const { return path_; }
    std::uint64_t current_bytes() const { return size_; }
    std::uint64_t files_deleted() const { return deleted_; }
    // The last error ("<path>: <reason>"), cleared by take_error().
    std::string take_error();
    // The files opened since the last call, oldest first (for the log).
    std::vector<std::string> take_opened() { return std::exchange(opened_, {}); }

  private:
    bool open_next(std::int64_t unix_seconds);
    bool write_all(std::span<const std::uint8_t> bytes);
    // Writes whole blocks; on an error keeps those that made it. `bytes` kept, `error` errno.
    struct Kept {
        std::size_t bytes;
        int error;
    };
    Kept write_whole_blocks(std::span<const std::uint8_t> blocks);
    void cut_back(std::uint64_t size);  // truncate to `size` and write from there
    static std::uint64_t count_blocks(std::span<const std::uint8_t> blocks);
    void enforce_total();
    void set_error(const std::string& path, int err);

    RecordFilesOptions options_;
    int fd_ = -1;
    std::string path_;
    std::uint64_t size_ = 0;
    bool has_packets_ = false;
    bool dirty_ = false;
    unsigned sequence_ = 0;
    std::uint64_t deleted_ = 0;
    std::string error_;
    std::vector<std::string> opened_;
};

}  // namespace gimbald::record
