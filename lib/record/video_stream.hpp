// The video side of a recording (docs/recording-format.md): one gimbal's interface
// `video:<name>` - the MPEG-TS it received (inbound, dissector `mp2t`, one PDU per UDP
// datagram) and the KLV sets gimbald generated for it (outbound, one set per PDU) - in order,
// with their times. What gimbal-replay --video sends and gimbal-export --format klv-csv reads.
// Pure.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "record/pcapng_reader.hpp"

namespace gimbal::record {

inline constexpr std::string_view video_prefix = "video:";

struct VideoStream {
    std::string gimbal;       // the gimbal's name (if_name without "video:")
    std::string description;  // if_description: "mp2t <input URL>"
    struct Chunk {
        std::int64_t time_us = 0;  // receive (or generation) time, microseconds since 1970
        bool generated = false;    // false: TS as received; true: a KLV set gimbald generated
        std::vector<std::uint8_t> bytes;
    };
    std::vector<Chunk> chunks;
    std::uint64_t ts_bytes = 0;
    std::uint64_t generated_sets = 0;
    Stop stop = Stop::none;
    std::string stop_message;
    std::vector<std::string> all_gimbals;  // every gimbal with a video interface in the file
};

// Reads `file` and collects the PDUs of interface `video:<name>` (empty name: the only video
// interface). False with `error` when the bytes are not a recording, or it has no such video
// (or several and no name). A cut-short tail is not an error (stop, stop_message).
bool load_video_stream(std::span<const std::uint8_t> file, const std::string& name,
                       VideoStream& out, std::string& error);

// Several files of one recording, in order (load_gimbal_files' rules). A file without the
// video interface is an error only when none of the files has it.
bool load_video_files(const std::vector<std::string>& paths, const std::string& name,
                      VideoStream& out, std::vector<std::string>& warnings, std::string& error);

}  // namespace gimbal::record
