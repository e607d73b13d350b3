#include "secret_file.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "regular_file.hpp"

namespace gimbal::daemon {

command::Result<std::string> read_secret_file(const std::string& path) {
    constexpr std::size_t max_bytes = 64 * 1024;  // a key, a password: never this much
    const FileCheck owner_only = [&path](const struct stat& st) -> std::optional<command::Error> {
        if ((st.st_mode & 077) == 0) return std::nullopt;
        return command::Error{
            command::code::forbidden,
            fmt::format("{}: readable by group or others (mode {:04o}); chmod 600 it", path,
                        st.st_mode & 07777)};
    };
    auto text = read_regular_file(path, max_bytes, owner_only);
    if (text) return text;
    const auto& e = text.error();
    if (e.message == path + ": " + std::strerror(ENOENT))
        return command::Error{e.code, path + ": missing"};  // what a key file lacks, plainly
    if (e.message.ends_with("larger than 64 KiB"))
        return command::Error{e.code, e.message + ": not a secret file"};
    return text;
}

}  // namespace gimbal::daemon
