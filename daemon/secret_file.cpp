#include "secret_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace gimbal::daemon {

command::Result<std::string> read_secret_file(const std::string& path) {
    namespace code = command::code;
    auto problem = [&path](command::ErrorCode c, std::string reason) {
        return command::Result<std::string>{c, fmt::format("{}: {}", path, reason)};
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0)
        return problem(code::unavailable, errno == ENOENT ? "missing" : std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        return problem(code::bad_request, "not a regular file");
    }
    if ((st.st_mode & 077) != 0) {
        ::close(fd);
        return problem(code::forbidden,
                       fmt::format("readable by group or others (mode {:04o}); chmod 600 it",
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
            return problem(code::unavailable, reason);
        }
        if (n == 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
        if (text.size() > 65536) {
            ::close(fd);
            return problem(code::bad_request, "larger than 64 KiB: not a secret file");
        }
    }
    ::close(fd);
    return text;
}

}  // namespace gimbal::daemon
