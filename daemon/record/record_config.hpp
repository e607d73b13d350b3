// `record` (contract section 12, docs/recording.md): the flight recorder; off unless set.
// Sizes are megabytes (10^6 bytes) and may be fractions (tests rotate at 0.05). Declared once
// here and read and written by the generic reader (lib/config/fields.hpp); RecorderOptions
// derives from it.
#pragma once

#include <string>

#include "config/fields.hpp"

namespace gimbal::daemon {

struct RecordConfig {
    std::string dir;
    double max_file_mb = 100;
    double max_total_mb = 2000;
    bool operator==(const RecordConfig&) const = default;
};

// The directory must exist and be writable now, so --check-config and start-up both name the
// path and the reason.
void check_record_dir(config::Fields& f, const std::string& dir);

template <class V>
void fields(V& v, RecordConfig& c) {
    if (v.string("dir", c.dir, config::Presence::required)) {
        if constexpr (V::reading) check_record_dir(v, c.dir);
    }
    v.number("max_file_mb", c.max_file_mb, {0.001, 1e6});
    v.number("max_total_mb", c.max_total_mb, {0.001, 1e9});
    if (c.max_total_mb < c.max_file_mb) v.problem("max_total_mb", "must be at least max_file_mb");
}

}  // namespace gimbal::daemon
