// One gimbal's KLV as STATE `video` and the `klv` command show it (contract section 17): the
// latest set - found in the stream or generated - with its bytes and its decoded JSON, and
// the counters. The stream's KLV units are searched for UAS Datalink sets (lib/klv); a set
// whose checksum is wrong is counted and ignored, as is one that does not parse. Pure: times
// (seconds, monotonic) are passed in.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "klv/ber.hpp"

namespace gimbald::video {

enum class KlvSource { stream, generated };
std::string_view to_string(KlvSource source);

class KlvTrack {
  public:
    // A stream counts as carrying KLV while a valid set came within this long.
    explicit KlvTrack(double stream_fresh_s = 2.0) : stream_fresh_s_(stream_fresh_s) {}

    // One KLV unit (PES payload) of the stream: the valid sets in it, each whole (key through
    // checksum), in order. Sets with a bad checksum or a malformed body are counted, not
    // returned.
    std::vector<gimbal::klv::Bytes> stream_unit(std::span<const std::uint8_t> unit, double now_s);
    // A set gimbald generated (key through checksum).
    void generated(gimbal::klv::Bytes set, double now_s);

    // A valid stream set arrived within stream_fresh_s.
    bool stream_fresh(double now_s) const;

    bool has_latest() const { return latest_.has_value(); }
    std::optional<KlvSource> source() const;
    const gimbal::klv::Bytes* latest_bytes() const;
    // The latest set decoded (klv::decode JSON), decoded once per set; null when none.
    const nlohmann::json& latest_json() const;
    double latest_age_s(double now_s) const;
    // Decoded JSON of the latest stream set (for klv_vs_telemetry); null when none.
    const nlohmann::json* latest_stream_json() const;

    std::uint64_t sets() const { return sets_; }
    std::uint64_t bad_checksums() const { return bad_checksums_; }
    std::uint64_t malformed() const { return malformed_; }

  private:
    struct Latest {
        gimbal::klv::Bytes bytes;
        KlvSource source = KlvSource::stream;
        double at_s = 0;
        mutable std::optional<nlohmann::json> decoded;  // filled on first use
    };

    double stream_fresh_s_;
    std::optional<Latest> latest_;
    std::optional<double> last_stream_s_;
    std::uint64_t sets_ = 0;
    std::uint64_t bad_checksums_ = 0;
    std::uint64_t malformed_ = 0;
};

}  // namespace gimbald::video
