// gimbals[].video (contract section 17): the gimbal's video input, what to do with its KLV
// and where to relay it. Declared once here as a fields() visit, read and written by the
// generic reader (lib/config/fields.hpp). Keys, ranges and defaults: docs/configuration.md,
// docs/video.md.
#pragma once

#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config/fields.hpp"
#include "video/tracking_config.hpp"
#include "video/url.hpp"

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
    // udp:// inputs: the sender the stream must come from, "host[:port]" (source_pin.hpp);
    // none: the first sender, pinned until it is silent for 5 s.
    std::optional<std::string> source;
    // Visual tracking (contract section 20, tracking_config.hpp); none: `track` is unavailable.
    std::optional<TrackingConfig> tracking;
    bool operator==(const VideoConfig&) const = default;
};

inline constexpr double min_klv_rate_hz = 0.1;
inline constexpr double max_klv_rate_hz = 60;
inline constexpr std::size_t max_outputs = 8;
inline constexpr std::size_t max_mission_id_bytes = 127;  // ST 0601 tag 3

inline constexpr std::array<gimbal::config::Named<KlvMode>, 4> klv_mode_names{
    {{"auto", KlvMode::automatic},
     {"parse", KlvMode::parse},
     {"generate", KlvMode::generate},
     {"off", KlvMode::off}}};

// Reading, in this section's own words (URLs checked for where they may appear, outputs that
// would feed the relay back into itself refused): docs/video.md.
using ProblemSink = std::function<void(std::string path, std::string message)>;
void read_video_fields(gimbal::config::Fields& f, VideoConfig& config);

template <class V>
void fields(V& v, VideoConfig& c) {
    if constexpr (V::reading) {
        read_video_fields(v, c);
    } else {
        // Written for logs and the protocols' option objects: an RTSP password is not shown.
        v.string("input", gimbal::video::redact_userinfo(c.input));
        v.choice("klv", c.klv, klv_mode_names);
        v.number("klv_rate_hz", c.klv_rate_hz, {min_klv_rate_hz, max_klv_rate_hz});
        v.set_json("outputs", c.outputs);
        v.optional_string("mission_id", c.mission_id);
        v.optional_string("source", c.source);
        if (c.tracking)
            v.section("tracking", [&](auto& t) { fields(t, *c.tracking); });
        else
            v.set_json("tracking", nullptr);
    }
}

}  // namespace gimbald::video
