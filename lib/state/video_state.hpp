// STATE `video` (contract section 17): a gimbal's video input and its KLV, as the daemon's
// video (daemon/video) reports it. The MAVLink camera reads it for its stream information.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace gimbal::state {

// `klv_vs_telemetry`: how far the stream's KLV lies from gimbald's own values, metres.
struct KlvOffsets {
    std::optional<double> sensor_m;
    std::optional<double> frame_center_m;
};

struct VideoState {
    std::string input;  // the configured URL, credentials removed
    bool connected = false;
    std::optional<std::string> codec;  // "h264", "h265"
    std::optional<int> width, height;  // pixels, once known
    std::optional<double> fps;
    std::uint64_t bitrate_bps = 0;
    std::optional<std::string> klv_source;  // "stream", "generated"
    // The latest KLV set as lib/klv decodes it (a codec's JSON), with its age; null: none.
    nlohmann::json klv = nullptr;
    std::uint64_t klv_sets = 0;
    std::uint64_t klv_bad_checksums = 0;
    std::uint64_t klv_refused = 0;
    std::optional<KlvOffsets> klv_vs_telemetry;  // nullopt until a stream set was compared
    std::optional<std::string> source;           // UDP: the sender in use
    std::uint64_t foreign_datagrams = 0;
    std::uint64_t dropped_datagrams = 0;
    std::uint64_t dropped_units = 0;
    std::uint64_t reconnects = 0;
    std::optional<std::string> last_error;
};

template <class V>
void fields(V& v, const KlvOffsets& o) {
    v.metres("sensor_m", o.sensor_m);
    v.metres("frame_center_m", o.frame_center_m);
}

template <class V>
void fields(V& v, const VideoState& s) {
    v.string("input", s.input);
    v.boolean("connected", s.connected);
    v.string("codec", s.codec);
    v.integer("width", s.width);
    v.integer("height", s.height);
    v.decimals("fps", s.fps, 3);
    v.integer("bitrate_bps", s.bitrate_bps);
    v.string("klv_source", s.klv_source);
    v.json("klv", s.klv);
    v.integer("klv_sets", s.klv_sets);
    v.integer("klv_bad_checksums", s.klv_bad_checksums);
    v.integer("klv_refused", s.klv_refused);
    v.object("klv_vs_telemetry", s.klv_vs_telemetry);
    v.string("source", s.source);
    v.integer("foreign_datagrams", s.foreign_datagrams);
    v.integer("dropped_datagrams", s.dropped_datagrams);
    v.integer("dropped_units", s.dropped_units);
    v.integer("reconnects", s.reconnects);
    v.string("last_error", s.last_error);
}

}  // namespace gimbal::state
