// H.264 / H.265 bitstream helpers: Annex B NAL splitting, NAL types, key-frame detection,
// parameter sets, and length-prefixed (AVCC/HVCC, as in MP4 and in libavformat's
// extradata) to Annex B conversion. Never decodes a picture.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "video/codec.hpp"

namespace gimbal::video {

using Bytes = std::vector<std::uint8_t>;
using ByteView = std::span<const std::uint8_t>;

// The NAL units of an Annex B byte stream (start codes 00 00 01 or 00 00 00 01), each
// without its start code and without trailing zero bytes. Bytes before the first start code
// are ignored.
std::vector<ByteView> split_annexb(ByteView stream);

// nal_unit_type from the NAL header (H.264: 5 bits; H.265: 6 bits); 0xFF for an empty NAL.
std::uint8_t nal_type(Codec codec, ByteView nal);

namespace h264 {
inline constexpr std::uint8_t idr = 5, sei = 6, sps = 7, pps = 8, aud = 9;
}
namespace h265 {
inline constexpr std::uint8_t bla_w_lp = 16, rsv_irap_23 = 23, vps = 32, sps = 33, pps = 34,
                              aud = 35, prefix_sei = 39;
}

bool is_vcl(Codec codec, std::uint8_t type);
bool is_parameter_set(Codec codec, std::uint8_t type);
// IDR (H.264 type 5) or IRAP (H.265 types 16..23): a decoder can start here.
bool is_key_nal(Codec codec, std::uint8_t type);
bool is_key_frame(Codec codec, ByteView annexb_au);

// The parameter sets a decoder needs before a key frame (VPS, SPS, PPS), kept as NAL units.
struct ParameterSets {
    std::vector<Bytes> nals;

    bool empty() const { return nals.empty(); }
    bool has_sps(Codec codec) const;
    // Replaces a set of the same type and id-less position (by type): in-band sets win.
    void update(Codec codec, ByteView nal);
    Bytes annexb() const;
};

// libavformat's extradata: an avcC (H.264, ISO 14496-15 5.3.3.1) or hvcC (H.265, 8.3.3.1)
// record - then the samples are length-prefixed - or Annex B parameter sets (RTSP's
// sprop-parameter-sets) - then they are Annex B already.
struct Extradata {
    int length_size = 0;  // 1, 2 or 4 for length-prefixed samples; 0 for Annex B
    ParameterSets sets;
};
std::optional<Extradata> parse_extradata(Codec codec, ByteView extradata);

// A length-prefixed sample to Annex B; nullopt when a length runs past the end.
std::optional<Bytes> length_prefixed_to_annexb(ByteView sample, int length_size);

// An Annex B access unit with `sets` inserted before its first VCL NAL when it is a key
// frame without its own SPS (the RTSP case: parameter sets only in the SDP). Other access
// units are returned unchanged.
Bytes with_parameter_sets(Codec codec, ByteView annexb_au, const ParameterSets& sets);

// Width and height in pixels after cropping, frame rate from VUI timing when present.
struct VideoFormat {
    int width = 0;
    int height = 0;
    std::optional<double> fps;
    friend bool operator==(const VideoFormat&, const VideoFormat&) = default;
};

// Parses a whole SPS NAL unit (with its NAL header, emulation prevention still in).
std::optional<VideoFormat> parse_sps(Codec codec, ByteView sps_nal);
// The format of the first SPS found in an Annex B access unit.
std::optional<VideoFormat> find_format(Codec codec, ByteView annexb_au);

}  // namespace gimbal::video
