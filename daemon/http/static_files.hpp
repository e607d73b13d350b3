// The console's static files (contract section 11, `GET /`): which file a request target
// names under the web root - never one outside it - and its Content-Type.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace gimbald::http {

// The path of a request target: without ?query and #fragment.
std::string_view target_path(std::string_view target);

// %XX decoded; nullopt for a bad escape or a decoded NUL.
std::optional<std::string> percent_decode(std::string_view text);

// The regular file under `root` that `target` names ("/" and ".../" mean index.html), or
// nullopt: a bad escape, a ".." or hidden (dot) segment, a backslash, a file that does not
// exist, or a symbolic link that leads outside the root.
std::optional<std::filesystem::path> resolve_static(const std::filesystem::path& root,
                                                    std::string_view target);

// By extension: text/html; charset=utf-8, application/javascript, ... else
// application/octet-stream.
std::string_view content_type(const std::filesystem::path& file);

// http.web_root when set; else the installed console directory, or the source tree's web/
// for a gimbald run from its build tree.
std::filesystem::path default_web_root();

}  // namespace gimbald::http
