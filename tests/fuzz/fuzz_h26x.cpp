// libFuzzer target for lib/video's H.264/H.265 helpers: the first byte picks the codec and
// a length size, the rest is used as an Annex B access unit, as a single NAL (SPS parser),
// as avcC/hvcC extradata and as a length-prefixed sample. Invariants: NAL views lie inside
// the input; a parsed SPS has a sane size; conversions keep every NAL byte.
#include <cstdio>
#include <cstdlib>

#include "video/nal.hpp"

namespace v = gimbal::video;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_h26x: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const v::Codec codec = (data[0] & 1) ? v::Codec::h265 : v::Codec::h264;
    const int length_size = 1 + ((data[0] >> 1) & 3);
    const std::span<const std::uint8_t> body(data + 1, size - 1);

    std::size_t nal_bytes = 0;
    for (const auto nal : v::split_annexb(body)) {
        if (nal.empty() || nal.data() < body.data() ||
            nal.data() + nal.size() > body.data() + body.size())
            fail("NAL view outside the input");
        nal_bytes += nal.size();
        (void)v::nal_type(codec, nal);
    }
    if (nal_bytes > body.size()) fail("NALs longer than the input");
    (void)v::is_key_frame(codec, body);

    if (const auto f = v::parse_sps(codec, body)) {
        if (f->width <= 0 || f->height <= 0 || f->width > 65536 || f->height > 65536)
            fail("SPS size out of range");
        if (f->fps && !(*f->fps > 0)) fail("SPS frame rate not positive");
    }
    (void)v::find_format(codec, body);

    if (const auto ex = v::parse_extradata(codec, body)) {
        if (ex->length_size != 0 &&
            (ex->length_size < 1 || ex->length_size > 4 || ex->length_size == 3))
            fail("bad length size from extradata");
        const auto fixed = v::with_parameter_sets(codec, body, ex->sets);
        if (!v::is_key_frame(codec, body) && fixed.size() != body.size())
            fail("a non-key unit was changed");
    }
    if (const auto annexb = v::length_prefixed_to_annexb(body, length_size)) {
        const auto nals = v::split_annexb(*annexb);
        std::size_t total = 0;
        for (const auto nal : nals) total += nal.size();
        if (total > body.size()) fail("conversion invented bytes");
    }
    return 0;
}
