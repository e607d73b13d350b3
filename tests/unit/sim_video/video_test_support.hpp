// Temporary directories and external tools (ffmpeg, ffprobe) for the encoded-video tests. Not
// a test file itself.
#pragma once

#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sim_video/h264_encoder.hpp"

namespace video_test {

class TempDir {
  public:
    TempDir() {
        char tmpl[] = "/tmp/gimbal_sim_video.XXXXXX";
        if (mkdtemp(tmpl)) path_ = tmpl;
    }
    ~TempDir() {
        std::error_code ec;
        if (!path_.empty()) std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    bool ok() const { return !path_.empty(); }

  private:
    std::filesystem::path path_;
};

// Standard output of a shell command; `status` gets its exit status.
inline std::string run(const std::string& command, int& status) {
    std::string out;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) {
        status = -1;
        return out;
    }
    std::array<char, 4096> buffer;
    std::size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
        out.append(buffer.data(), n);
    status = pclose(pipe);
    return out;
}

inline bool have_tool(const std::string& name) {
    int status = 0;
    run(name + " -version >/dev/null 2>&1", status);
    return status == 0;
}

// The access units back to back: a raw .h264 elementary stream.
inline void write_stream(const std::string& path,
                         const std::vector<gimbal::sim_video::AccessUnit>& units) {
    std::ofstream out(path, std::ios::binary);
    for (const auto& u : units)
        out.write(reinterpret_cast<const char*>(u.annex_b.data()),
                  static_cast<std::streamsize>(u.annex_b.size()));
}

inline std::vector<std::uint8_t> read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace video_test
