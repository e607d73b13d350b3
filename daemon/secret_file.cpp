#include "secret_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace gimbal::daemon {

std::variant<std::string, std::string> read_private_file(const std::string& path) {
    using Result = std::variant<std::string, std::string>;
    auto problem = [&path](std::string reason) {
        return Result{std::in_place_index<1>, fmt::format("{}: {}", path, reason)};
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) return problem(errno == ENOENT ? "missing" : std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        return problem("not a regular file");
    }
    if ((st.st_mode & 077) != 0) {
        ::close(fd);
        return problem(fmt::format("readable by group or others (mode {:04o}); chmod 600 it",
                                   st.st_mode & 07777));
    }
    std::string text;
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const std::string reason = std::strerror(errno);
            ::close(fd);
            return problem(reason);
        }
        if (n == 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
        if (text.size() > 65536) {
            ::close(fd);
            return problem("larger than 64 KiB: not a secret file");
        }
    }
    ::close(fd);
    return Result{std::in_place_index<0>, std::move(text)};
}

}  // namespace gimbal::daemon
