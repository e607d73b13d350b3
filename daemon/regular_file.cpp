#include "regular_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace gimbal::daemon {

namespace {

namespace code = command::code;

command::Error problem(const std::string& path, command::ErrorCode c, const std::string& reason) {
    return command::Error{c, fmt::format("{}: {}", path, reason)};
}

std::string kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a plain file";
}

// The file open for reading, checked to be a regular file; closes it on every refusal.
class OpenFile {
  public:
    explicit OpenFile(const std::string& path) : path_(path) {
        // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
        if (fd_ < 0) {
            error_ = problem(path, code::unavailable, std::strerror(errno));
            return;
        }
        if (::fstat(fd_, &st_) != 0) {
            error_ = problem(path, code::unavailable, std::strerror(errno));
        } else if (!S_ISREG(st_.st_mode)) {
            error_ = problem(path, code::bad_request,
                             "not a regular file (" + kind_of(st_.st_mode) + ")");
        }
    }
    ~OpenFile() {
        if (fd_ >= 0) ::close(fd_);
    }
    OpenFile(const OpenFile&) = delete;
    OpenFile& operator=(const OpenFile&) = delete;

    const std::optional<command::Error>& error() const { return error_; }
    const struct stat& status() const { return st_; }
    int fd() const { return fd_; }

  private:
    std::string path_;
    int fd_ = -1;
    struct stat st_ {};
    std::optional<command::Error> error_;
};

}  // namespace

std::string size_text(std::size_t bytes) {
    if (bytes >= 1024 * 1024 && bytes % (1024 * 1024) == 0)
        return fmt::format("{} MiB", bytes / (1024 * 1024));
    if (bytes >= 1024 && bytes % 1024 == 0) return fmt::format("{} KiB", bytes / 1024);
    return fmt::format("{} bytes", bytes);
}

command::Result<std::string> read_regular_file(const std::string& path, std::size_t max_bytes,
                                               const FileCheck& check) {
    OpenFile file(path);
    if (file.error()) return *file.error();
    if (check)
        if (auto refused = check(file.status())) return *refused;
    const auto too_large = [&] {
        return problem(path, code::bad_request, "larger than " + size_text(max_bytes));
    };
    if (static_cast<std::size_t>(file.status().st_size) > max_bytes) return too_large();
    std::string text;
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(file.fd(), buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return problem(path, code::unavailable, std::strerror(errno));
        if (n == 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
        if (text.size() > max_bytes) return too_large();  // it grew while being read
    }
    return text;
}

std::optional<command::Error> check_regular_file(const std::string& path) {
    OpenFile file(path);
    return file.error();
}

}  // namespace gimbal::daemon
