// H.264 Annex B byte streams (ITU-T H.264 Annex B): NAL units after 00 00 01 or 00 00 00 01
// start codes, and the codec string browsers want for them (RFC 6381 "avc1.PPCCLL": profile_idc,
// the constraint-flags byte, level_idc from the sequence parameter set). Pure.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace gimbal::sim_video {

// nal_unit_type values used here (H.264 Table 7-1).
enum class NalType : std::uint8_t {
    slice = 1,
    idr_slice = 5,
    sei = 6,
    sps = 7,
    pps = 8,
    aud = 9,
};

struct NalUnit {
    std::uint8_t type = 0;                // nal_unit_type, the low five bits of the first byte
    std::span<const std::uint8_t> bytes;  // from the NAL header, start code excluded
};

// The NAL units of an Annex B stream, in order. Bytes before the first start code are skipped.
std::vector<NalUnit> nal_units(std::span<const std::uint8_t> annex_b);

// "avc1.42C01E" from the first SPS in the stream; nullopt without one.
std::optional<std::string> avc_codec_string(std::span<const std::uint8_t> annex_b);

}  // namespace gimbal::sim_video
