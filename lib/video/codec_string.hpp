// The codec string a browser's decoder is configured with (WebCodecs VideoDecoder, Media
// Source Extensions' isTypeSupported), read from a sequence parameter set: RFC 6381 3.3
// for H.264 ("avc1.PPCCLL": profile_idc, the constraint flags byte, level_idc, in hex) and
// ISO/IEC 14496-15 Annex E.3 for H.265 ("hvc1.1.6.L93.B0"). Nothing else of the SPS is read.
#pragma once

#include <optional>
#include <string>

#include "video/codec.hpp"
#include "video/nal.hpp"

namespace gimbal::video {

// `sps_nal`: a whole SPS NAL unit with its header (emulation prevention still in);
// nullopt when it is too short or not an SPS.
std::optional<std::string> codec_string(Codec codec, ByteView sps_nal);

// The codec string of the first SPS in an Annex B access unit.
std::optional<std::string> find_codec_string(Codec codec, ByteView annexb_au);

}  // namespace gimbal::video
