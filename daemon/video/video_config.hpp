// gimbals[].video (contract section 17): the gimbal's video input, what to do with its KLV
// and where to relay it. This section's reading lives here, beside the code it configures;
// daemon/config.cpp calls read_video_config() for each gimbal that has the key and writes it
// back with to_json(). Keys, ranges and defaults: docs/configuration.md, docs/video.md.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gimbald::video {

enum class KlvMode {
    automatic,  // "auto": parse the stream's KLV when it has some, else generate from STATE
    parse,      // only the stream's KLV (none is generated)
    generate,   // always generate from STATE (the stream's KLV is not used)
    off,        // no KLV at all: nothing parsed, generated or sent; outputs carry video only
};
std::string_view to_string(KlvMode mode);

struct VideoConfig {
    std::string input;  // udp://... or rtsp://... (checked by gimbal::video::parse_video_url)
    KlvMode klv = KlvMode::automatic;
    double klv_rate_hz = 10;                // generated sets per second
    std::vector<std::string> outputs;       // udp://... (MPEG-TS) or klv-udp://...
    std::optional<std::string> mission_id;  // KLV tag 3 of generated sets
    bool operator==(const VideoConfig&) const = default;
};

inline constexpr double min_klv_rate_hz = 0.1;
inline constexpr double max_klv_rate_hz = 60;
inline constexpr std::size_t max_outputs = 8;
inline constexpr std::size_t max_mission_id_bytes = 127;  // ST 0601 tag 3

// The section's keys. Unknown ones are reported by daemon/config.cpp, in the wording (and
// with the "did you mean" of) every other section.
inline constexpr std::string_view video_keys[] = {"input", "klv", "klv_rate_hz", "outputs",
                                                  "mission_id"};

// Reads one gimbal's `video` object at JSON path `path` ("gimbals[0].video"); every problem
// of a known key goes to `problem(path, message)`. Returns the section as far as it could be read
// (only meaningful when no problem was reported).
using ProblemSink = std::function<void(std::string path, std::string message)>;
VideoConfig read_video_config(const nlohmann::json& value, const std::string& path,
                              const ProblemSink& problem);

// Every key, with its value (the inverse of read_video_config).
nlohmann::json to_json(const VideoConfig& config);

}  // namespace gimbald::video
