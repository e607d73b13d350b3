// The gimbal side of a recording: the bytes one gimbal sent (its interface's inbound PDUs,
// in order, with their receive times), which is what gimbal-replay plays back and
// gimbal-export decodes. Pure.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "record/pcapng_reader.hpp"

namespace gimbal::record {

struct GimbalInterfaceInfo {
    std::string name;         // the gimbal's name (if_name without "gimbal:")
    std::string protocol;     // a registry name, or "" when the recording does not say
    std::string description;  // if_description
};

struct GimbalStream {
    GimbalInterfaceInfo gimbal;
    struct Chunk {
        std::int64_t time_us = 0;  // receive time, microseconds since the Unix epoch
        std::vector<std::uint8_t> bytes;
    };
    std::vector<Chunk> chunks;
    std::uint64_t bytes = 0;
    std::uint64_t outbound_pdus = 0;  // commands gimbald sent (not played back)
    std::uint64_t bad_pdus = 0;       // inbound packets whose exported-PDU tags were malformed
    Stop stop = Stop::none;           // how reading the file ended
    std::string stop_message;
    std::vector<GimbalInterfaceInfo> all_gimbals;  // every gimbal interface in the file
};

// Reads `file` and collects the inbound PDUs of gimbal `name` (empty: the only gimbal in the
// file). Interfaces are matched by name in every section. False with `error` set when the
// bytes are not a recording at all, hold no such gimbal, or several gimbals and no name.
// A truncated or damaged tail is not an error: stop/stop_message report it.
bool load_gimbal_stream(std::span<const std::uint8_t> file, const std::string& name,
                        GimbalStream& out, std::string& error);

// Several files of one recording in order (gimbald rotates files; each stands alone): reads
// each with load_gimbal_stream and appends its chunks. A file cut short or damaged does not
// end the list; `warnings` gets one line per such file ("FILE: truncated (...)"). False with
// `error` ("FILE: reason") when a file cannot be read, is not a recording, or lacks the gimbal.
bool load_gimbal_files(const std::vector<std::string>& paths, const std::string& name,
                       GimbalStream& out, std::vector<std::string>& warnings, std::string& error);

}  // namespace gimbal::record
