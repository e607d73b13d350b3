// libFuzzer target for the Viewpro codec: both framers fed the input in chunks, every frame
// they deliver decoded, shown as JSON and (gimbal output) re-encoded; the whole-frame
// checkers and the ISO time parser on the raw input. Any crash, sanitizer report or broken
// invariant aborts.
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "protocols/viewpro/codec/viewpro.hpp"

namespace v = gimbal::viewpro;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_viewpro: %s\n", what);
    std::abort();
}

// Chunk sizes come from the input itself so the fuzzer explores splits too.
template <class Framer, class OnFrame>
std::size_t push_chunked(Framer& framer, std::span<const std::uint8_t> data, OnFrame&& on_frame) {
    std::size_t delivered = 0;
    std::size_t i = 0;
    while (i < data.size()) {
        const std::size_t chunk = 1 + data[i] % 97;
        const std::size_t n = std::min(chunk, data.size() - i);
        framer.push(data.subspan(i, n), [&](const auto& frame) {
            delivered += frame.size;
            on_frame(frame);
        });
        i += n;
    }
    return delivered;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> input(data, size);

    v::OutputFramer out;
    const std::size_t out_bytes = push_chunked(out, input, [](const v::OutputFrame& frame) {
        const auto decoded = v::decode_output(frame);
        if (!decoded) fail("a framed OUTx frame does not decode");
        (void)v::to_json(*decoded).dump();
        const auto again = v::make_output_frame(v::encode_output(*decoded));
        if (!again || again->format != frame.format || again->size != frame.size)
            fail("a decoded OUTx frame does not re-encode to a frame of its format");
    });
    if (out.stats().bytes != out_bytes + out.stats().dropped_bytes + out.pending_bytes())
        fail("output framer lost track of bytes");

    v::InputFramer in;
    const std::size_t in_bytes = push_chunked(in, input, [](const v::InputFrame& frame) {
        (void)v::decode_vehicle(frame);
        (void)v::decode_in3(frame);
        (void)v::decode_mode(frame);
        (void)v::decode_shift(frame);
        (void)v::to_json(frame).dump();
    });
    if (in.stats().bytes != in_bytes + in.stats().dropped_bytes + in.pending_bytes())
        fail("input framer lost track of bytes");

    (void)v::make_output_frame(input);
    (void)v::make_input_frame(input);
    (void)v::parse_iso8601(std::string_view(reinterpret_cast<const char*>(data), size));
    return 0;
}
