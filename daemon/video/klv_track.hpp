// One gimbal's KLV as STATE `video` and the `klv` command show it (contract section 17): the
// latest set - found in the stream or generated - with its bytes and its decoded JSON, and
// the counters. The stream's sets arrive already checked and decoded off the io thread
// (klv::check_sets on the input's worker): this only keeps the latest and counts. The JSON
// shown is at most max_json_bytes (8 KiB, contract section 14 v4; klv::fit_json says what is
// left out). Pure: times (seconds, monotonic) are passed in.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "klv/ber.hpp"
#include "klv/checked_sets.hpp"

namespace gimbald::video {

enum class KlvSource { stream, generated };
std::string_view to_string(KlvSource source);

class KlvTrack {
  public:
    // STATE `video.klv` is at most 8 KiB of JSON with its age_s; the decoded set leaves room
    // for that.
    static constexpr std::size_t max_state_json_bytes = 8 * 1024;
    static constexpr std::size_t max_json_bytes = max_state_json_bytes - 64;

    // A stream counts as carrying KLV while a valid set came within this long.
    explicit KlvTrack(double stream_fresh_s = 2.0) : stream_fresh_s_(stream_fresh_s) {}

    // The checked sets of the stream's KLV units (in order) and what was refused with them.
    void stream_sets(gimbal::klv::CheckedSets sets, double now_s);
    // A set gimbald generated (key through checksum).
    void generated(gimbal::klv::Bytes set, double now_s);

    // A valid stream set arrived within stream_fresh_s.
    bool stream_fresh(double now_s) const;

    bool has_latest() const { return latest_.has_value(); }
    std::optional<KlvSource> source() const;
    const gimbal::klv::Bytes* latest_bytes() const;
    // The latest set decoded (klv::decode JSON, cut by fit_json to max_json_bytes); null
    // when none.
    const nlohmann::json& latest_json() const;
    double latest_age_s(double now_s) const;
    // Decoded JSON of the latest stream set (for klv_vs_telemetry); null when none.
    const nlohmann::json* latest_stream_json() const;

    std::uint64_t sets() const { return sets_; }
    std::uint64_t bad_checksums() const { return bad_checksums_; }
    // Stream sets refused before they were decoded: over 64 KiB or 1024 items, malformed, or
    // past the number taken from one datagram.
    std::uint64_t refused() const { return refused_; }

  private:
    struct Latest {
        gimbal::klv::Bytes bytes;
        KlvSource source = KlvSource::stream;
        double at_s = 0;
        mutable std::optional<nlohmann::json> decoded;  // generated sets: filled on first use
    };

    double stream_fresh_s_;
    std::optional<Latest> latest_;
    std::optional<double> last_stream_s_;
    std::uint64_t sets_ = 0;
    std::uint64_t bad_checksums_ = 0;
    std::uint64_t refused_ = 0;
};

}  // namespace gimbald::video
