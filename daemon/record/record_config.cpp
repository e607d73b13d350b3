#include "record/record_config.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cerrno>
#include <cstring>

namespace gimbal::daemon {

void check_record_dir(config::Fields& f, const std::string& dir) {
    struct stat info {};
    if (dir.empty())
        f.problem("dir", "must not be empty");
    else if (::stat(dir.c_str(), &info) != 0)
        f.problem("dir", fmt::format("{}: {}", dir, std::strerror(errno)));
    else if (!S_ISDIR(info.st_mode))
        f.problem("dir", fmt::format("{}: not a directory", dir));
    else if (::access(dir.c_str(), W_OK | X_OK) != 0)
        f.problem("dir", fmt::format("{}: not writable: {}", dir, std::strerror(errno)));
}

}  // namespace gimbal::daemon
