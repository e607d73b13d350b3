#include "static_files.hpp"

#include <algorithm>
#include <array>
#include <system_error>
#include <utility>
#include <vector>

namespace gimbald::http {

namespace fs = std::filesystem;

std::string_view target_path(std::string_view target) {
    const auto end = target.find_first_of("?#");
    return end == std::string_view::npos ? target : target.substr(0, end);
}

std::optional<std::string> percent_decode(std::string_view text) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (c == '%') {
            if (i + 2 >= text.size()) return std::nullopt;
            const int hi = hex(text[i + 1]);
            const int lo = hex(text[i + 2]);
            if (hi < 0 || lo < 0) return std::nullopt;
            c = static_cast<char>(hi * 16 + lo);
            i += 2;
        }
        if (c == '\0') return std::nullopt;
        out += c;
    }
    return out;
}

std::optional<fs::path> resolve_static(const fs::path& root, std::string_view target) {
    const auto decoded = percent_decode(target_path(target));
    if (!decoded || decoded->empty() || decoded->front() != '/') return std::nullopt;
    fs::path relative;
    std::size_t start = 1;
    while (start <= decoded->size()) {
        auto end = decoded->find('/', start);
        if (end == std::string::npos) end = decoded->size();
        const std::string_view segment = std::string_view(*decoded).substr(start, end - start);
        if (!segment.empty()) {
            // ".." would climb out; dot files (.git, .htpasswd) are never part of the console.
            if (segment.front() == '.' || segment.find('\\') != std::string_view::npos)
                return std::nullopt;
            relative /= std::string(segment);
        }
        start = end + 1;
    }
    std::error_code ec;
    fs::path file = root / relative;
    if (decoded->back() == '/' || fs::is_directory(file, ec)) file /= "index.html";
    const fs::path real_root = fs::canonical(root, ec);
    if (ec) return std::nullopt;
    const fs::path real_file = fs::canonical(file, ec);
    if (ec || !fs::is_regular_file(real_file, ec)) return std::nullopt;
    // A symbolic link inside the root must not lead out of it.
    const auto [root_end, file_it] =
        std::mismatch(real_root.begin(), real_root.end(), real_file.begin(), real_file.end());
    if (root_end != real_root.end()) return std::nullopt;
    return real_file;
}

std::string_view content_type(const fs::path& file) {
    static const std::array<std::pair<std::string_view, std::string_view>, 16> types = {{
        {".html", "text/html; charset=utf-8"},
        {".htm", "text/html; charset=utf-8"},
        {".css", "text/css; charset=utf-8"},
        {".js", "text/javascript; charset=utf-8"},
        {".mjs", "text/javascript; charset=utf-8"},
        {".json", "application/json"},
        {".svg", "image/svg+xml"},
        {".png", "image/png"},
        {".jpg", "image/jpeg"},
        {".jpeg", "image/jpeg"},
        {".gif", "image/gif"},
        {".ico", "image/x-icon"},
        {".woff2", "font/woff2"},
        {".txt", "text/plain; charset=utf-8"},
        {".map", "application/json"},
        {".webp", "image/webp"},
    }};
    const std::string ext = file.extension().string();
    for (const auto& [suffix, type] : types)
        if (ext == suffix) return type;
    return "application/octet-stream";
}

fs::path default_web_root() {
    std::error_code ec;
    // A binary inside the build tree serves the checkout's web/ (scripts/run-sim.sh).
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path build_dir = GIMBALD_BUILD_DIR;
        const auto [b, e] =
            std::mismatch(build_dir.begin(), build_dir.end(), exe.begin(), exe.end());
        if (b == build_dir.end()) return GIMBALD_SOURCE_WEB_DIR;
    }
    return GIMBALD_INSTALLED_WEB_DIR;
}

}  // namespace gimbald::http
