#include "track/track_program.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace gimbald::track {

std::string find_track_program() {
    if (const char* env = std::getenv("GIMBAL_TRACK"); env != nullptr && *env != 0) return env;
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return "gimbal-track";
    const auto dir = self.parent_path();
    const std::vector<std::filesystem::path> candidates{dir / "gimbal-track",
                                                        dir / ".." / "bin" / "gimbal-track",
                                                        dir / ".." / "tools" / "gimbal-track"};
    for (const auto& c : candidates)
        if (::access(c.c_str(), X_OK) == 0) return c.lexically_normal().string();
    return candidates.front().string();
}

}  // namespace gimbald::track
