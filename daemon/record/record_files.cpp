#include "record/record_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <system_error>
#include <utility>

#include "record/pcapng_writer.hpp"

namespace gimbald::record {

namespace fs = std::filesystem;

std::string recording_file_name(std::int64_t unix_seconds, unsigned sequence) {
    const auto t = static_cast<std::time_t>(unix_seconds);
    std::tm utc{};
    gmtime_r(&t, &utc);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &utc);
    return fmt::format("gimbald-{}-{:04}.pcapng", stamp, sequence);
}

bool is_recording_file_name(std::string_view name) {
    // gimbald-YYYYMMDDTHHMMSSZ-NNNN.pcapng (NNNN may grow past 4 digits)
    constexpr std::string_view prefix = "gimbald-", suffix = ".pcapng";
    if (name.size() < prefix.size() + 16 + 5 + suffix.size()) return false;
    if (!name.starts_with(prefix) || !name.ends_with(suffix)) return false;
    const auto stamp = name.substr(prefix.size(), 16);
    for (std::size_t i = 0; i < stamp.size(); ++i) {
        const char c = stamp[i];
        const bool ok = i == 8 ? c == 'T' : i == 15 ? c == 'Z' : (c >= '0' && c <= '9');
        if (!ok) return false;
    }
    const auto seq =
        name.substr(prefix.size() + 16, name.size() - prefix.size() - 16 - suffix.size());
    if (seq.size() < 5 || seq[0] != '-') return false;
    return std::all_of(seq.begin() + 1, seq.end(), [](char c) { return c >= '0' && c <= '9'; });
}

RecordFiles::RecordFiles(RecordFilesOptions options) : options_(std::move(options)) {}

RecordFiles::~RecordFiles() {
    close();
}

void RecordFiles::set_error(const std::string& path, int err) {
    error_ = path + ": " + std::strerror(err);
}

std::string RecordFiles::take_error() {
    return std::exchange(error_, std::string());
}

std::string RecordFiles::open_first(std::int64_t unix_seconds) {
    if (!open_next(unix_seconds)) return take_error();
    return {};
}

bool RecordFiles::open_next(std::int64_t unix_seconds) {
    close();
    // O_EXCL: a name already taken (a restart within the same second) moves to the next one.
    for (int attempt = 0; attempt < 1000; ++attempt) {
        const auto path = (options_.dir / recording_file_name(unix_seconds, ++sequence_)).string();
        const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0640);
        if (fd < 0) {
            if (errno == EEXIST) continue;
            set_error(path, errno);
            return false;
        }
        fd_ = fd;
        path_ = path;
        size_ = 0;
        has_packets_ = false;
        if (!write_all(options_.header)) {
            const int err = errno;
            close();
            ::unlink(path.c_str());
            set_error(path, err);
            return false;
        }
        opened_.push_back(path);
        enforce_total();
        return true;
    }
    set_error((options_.dir / "gimbald-*.pcapng").string(), EEXIST);
    return false;
}

bool RecordFiles::write_all(std::span<const std::uint8_t> bytes) {
    const std::uint64_t before = size_;
    while (!bytes.empty()) {
        const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            cut_back(before);
            errno = err;
            return false;
        }
        bytes = bytes.subspan(static_cast<std::size_t>(n));
        size_ += static_cast<std::uint64_t>(n);
    }
    dirty_ = true;
    return true;
}

void RecordFiles::cut_back(std::uint64_t size) {
    if (::ftruncate(fd_, static_cast<off_t>(size)) == 0)
        ::lseek(fd_, static_cast<off_t>(size), SEEK_SET);
    size_ = size;
}

RecordFiles::Kept RecordFiles::write_whole_blocks(std::span<const std::uint8_t> blocks) {
    const std::uint64_t before = size_;
    std::size_t written = 0;
    while (written < blocks.size()) {
        const ssize_t n = ::write(fd_, blocks.data() + written, blocks.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) break;
        written += static_cast<std::size_t>(n);
        size_ += static_cast<std::uint64_t>(n);
    }
    if (written > 0) dirty_ = true;
    if (written == blocks.size()) return {written, 0};
    const int err = errno;
    // A nearly full disk (or a file-size limit) took part of it: keep every whole block that
    // made it, cut the one it stopped inside off, so the file ends with whole blocks.
    std::size_t kept = 0;
    while (kept < blocks.size()) {
        const std::uint32_t len = gimbal::record::block_length(blocks.subspan(kept));
        if (len < 12 || kept + len > written) break;
        kept += len;
    }
    if (kept != written) cut_back(before + kept);
    return {kept, kept == blocks.size() ? 0 : err};
}

std::uint64_t RecordFiles::count_blocks(std::span<const std::uint8_t> blocks) {
    std::uint64_t n = 0;
    for (std::size_t at = 0; at < blocks.size();) {
        const std::uint32_t len = gimbal::record::block_length(blocks.subspan(at));
        if (len < 12) break;
        at += len;
        ++n;
    }
    return n;
}

std::uint64_t RecordFiles::write(std::span<const std::uint8_t> blocks, std::int64_t unix_seconds) {
    std::uint64_t failed = 0;
    while (!blocks.empty()) {
        // The longest run of whole blocks that fits in the current file (at least one block
        // when the file holds no packet yet, so a tiny max_file_bytes still makes progress).
        std::size_t run = 0;
        std::uint64_t packets = 0;
        while (run < blocks.size()) {
            const std::uint32_t len = gimbal::record::block_length(blocks.subspan(run));
            if (len < 12 || len > blocks.size() - run) {
                run = blocks.size();  // cannot happen: the recorder appends whole blocks
                break;
            }
            const bool first = run == 0 && !has_packets_;
            if (!first && size_ + run + len > options_.max_file_bytes) break;
            run += len;
            ++packets;
        }
        if (fd_ < 0 || (run == 0 && has_packets_)) {
            if (!open_next(unix_seconds)) {
                // No file to write to: count every packet of this chunk as lost.
                return failed + count_blocks(blocks);
            }
            continue;
        }
        const Kept kept = write_whole_blocks(blocks.first(run));
        if (kept.bytes > 0) has_packets_ = true;
        if (kept.bytes < run) {
            set_error(path_, kept.error);
            failed += packets - count_blocks(blocks.first(kept.bytes));
        }
        blocks = blocks.subspan(run);
    }
    return failed;
}

void RecordFiles::enforce_total() {
    std::error_code ec;
    std::vector<std::pair<std::string, std::uint64_t>> files;
    for (const auto& entry : fs::directory_iterator(options_.dir, ec)) {
        const auto name = entry.path().filename().string();
        if (!is_recording_file_name(name)) continue;
        std::error_code size_ec;
        const auto size = entry.file_size(size_ec);
        if (!size_ec) files.emplace_back(entry.path().string(), size);
    }
    std::sort(files.begin(), files.end());  // names sort by start time
    std::uint64_t total = 0;
    for (const auto& f : files) total += f.second;
    // The current file is never deleted; it counts with the size it will grow to.
    total += options_.max_file_bytes > size_ ? options_.max_file_bytes - size_ : 0;
    for (const auto& [path, size] : files) {
        if (total <= options_.max_total_bytes) break;
        if (path == path_) continue;
        if (::unlink(path.c_str()) == 0) {
            total -= size;
            ++deleted_;
        }
    }
}

void RecordFiles::sync() {
    if (fd_ >= 0 && dirty_) {
        ::fdatasync(fd_);
        dirty_ = false;
    }
}

void RecordFiles::close() {
    if (fd_ < 0) return;
    sync();
    ::close(fd_);
    fd_ = -1;
}

}  // namespace gimbald::record
