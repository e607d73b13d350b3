// The visual track side of a recording: the records of one gimbal's interface
// `track:<gimbal>` (track_records.hpp), in order, with their times - what gimbal-export
// writes as the object's track. Pure apart from reading the files.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "record/pcapng_reader.hpp"
#include "record/track_records.hpp"

namespace gimbal::record {

struct TrackStream {
    std::string gimbal;
    bool found = false;  // the recording has the interface (the gimbal had tracking configured)
    std::vector<TrackRecord> records;
    std::uint64_t unreadable = 0;  // PDUs on the interface that are no track record
};

// Appends the records of gimbal `gimbal`'s track interface in `file` to `out` (matched by
// name in every section). False with `error` only when the bytes are no recording; a
// cut-short or damaged tail ends the file quietly (the gimbal stream's loader reports it).
bool load_track_stream(std::span<const std::uint8_t> file, const std::string& gimbal,
                       TrackStream& out, std::string& error);

// Several files of one recording, in order. A recording without the interface is no error:
// `found` stays false. False with `error` ("FILE: reason") when a file cannot be read or is
// no recording.
bool load_track_files(const std::vector<std::string>& paths, const std::string& gimbal,
                      TrackStream& out, std::string& error);

}  // namespace gimbal::record
