// libFuzzer target for the SIYI protocol (lib/protocols/siyi): the framer fed the input in
// chunks it chooses itself, every frame it delivers decoded in both directions, re-encoded
// and shown as JSON; every message declaration decoding the raw input; and the simulated
// gimbal receiving the input as a controller's bytes, whose every output frame must frame and
// decode cleanly. Any crash, sanitizer report or broken invariant aborts.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/codec/json.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "protocols/siyi/sim/siyi_sim.hpp"

namespace s = gimbal::siyi;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_siyi: %s\n", what);
    std::abort();
}

// A decoded message encodes to its declared length, and decoding that again gives the same
// bytes (the second pass is exact: rounding happened in the first).
template <class M>
void check_roundtrip(const M& m) {
    const s::Payload once = s::encode_payload(m);
    if (once.size != s::max_length<M>()) fail("an encoder wrote a length other than declared");
    const auto again = s::decode<M>(once.view());
    if (!again.ok()) fail("an encoded message does not decode");
    const s::Payload twice = s::encode_payload(again.value);
    if (twice.size != once.size ||
        !std::equal(once.view().begin(), once.view().end(), twice.view().begin()))
        fail("a message does not round-trip");
    (void)s::to_json(m).dump();
}

void check_frame(const s::Frame& frame) {
    const auto bytes = s::frame_bytes(frame);
    if (bytes.size() != frame.wire_size()) fail("a frame's size is not its wire size");
    const auto again = s::make_frame(bytes);
    if (!again || again->cmd != frame.cmd || again->seq != frame.seq || again->ctrl != frame.ctrl)
        fail("a delivered frame does not re-frame");
    for (const auto direction : {s::Direction::to_gimbal, s::Direction::from_gimbal})
        (void)s::frame_to_json(frame, direction).dump();
    if (const auto d = s::decode_to_gimbal(frame); d.ok())
        std::visit([](const auto& m) { check_roundtrip(m); }, d.value);
    if (const auto d = s::decode_from_gimbal(frame); d.ok())
        std::visit([](const auto& m) { check_roundtrip(m); }, d.value);
}

void decode_every_declaration(std::span<const std::uint8_t> input) {
    const auto each = [&]<class M>(M*) {
        const auto d = s::decode<M>(input);
        if (d.ok() != (input.size() >= s::min_length<M>()))
            fail("a decoder's verdict disagrees with its declared minimum length");
        if (d.ok()) check_roundtrip(d.value);
    };
    s::for_each_message(s::ToGimbalList{}, each);
    s::for_each_message(s::FromGimbalList{}, each);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> input(data, size);

    // The framer, in chunks the input chooses.
    s::Framer framer;
    std::uint64_t delivered = 0;
    for (std::size_t i = 0; i < input.size();) {
        const std::size_t n = std::min<std::size_t>(1 + input[i] % 97, input.size() - i);
        framer.push(input.subspan(i, n), [&](const s::Frame& f) {
            delivered += f.wire_size();
            check_frame(f);
        });
        i += n;
    }
    const auto& st = framer.stats();
    if (st.bytes != delivered + st.dropped_bytes + framer.pending_bytes())
        fail("the framer lost track of bytes");
    (void)s::make_frame(input);

    decode_every_declaration(input);

    // The simulated gimbal: the input as a controller's bytes, time advancing between chunks.
    gimbal::protocols::SiyiSimOptions options;
    options.model = s::all_models[size > 0 ? data[0] % s::all_models.size() : 0];
    options.angle_noise_deg = size > 1 ? data[1] % 3 : 0;
    gimbal::protocols::SiyiSim sim(options);
    std::vector<std::uint8_t> out;
    double t = 0;
    for (std::size_t i = 0; i < input.size();) {
        const std::uint8_t control = input[i];
        const std::size_t n = std::min<std::size_t>(1 + control % 61, input.size() - i);
        sim.receive(input.subspan(i, n), t);
        t += 0.005 * (control % 11);
        sim.advance(t, out);
        i += n;
    }
    sim.advance(t + 0.5, out);
    s::Framer replies;
    replies.push(out, [](const s::Frame& f) {
        if (!s::decode_from_gimbal(f).ok()) fail("the simulated gimbal sent an undecodable frame");
        if (!f.is_ack()) fail("the simulated gimbal sent a frame without ack_pack");
    });
    if (replies.stats().dropped_bytes != 0 || replies.pending_bytes() != 0)
        fail("the simulated gimbal sent bytes that are not whole frames");
    if (!std::isfinite(sim.yaw_deg()) || !std::isfinite(sim.pitch_deg()) ||
        !std::isfinite(sim.zoom()))
        fail("the simulated gimbal's state is not finite");
    const auto& m = sim.model();
    if (sim.pitch_deg() < m.pitch_min || sim.pitch_deg() > m.pitch_max)
        fail("the simulated gimbal's pitch left its limits");
    if (!m.yaw_continuous && (sim.yaw_deg() < m.yaw_min || sim.yaw_deg() > m.yaw_max))
        fail("the simulated gimbal's yaw left its limits");
    if (sim.zoom() < 1.0 || sim.zoom() > m.zoom_max) fail("the simulated zoom left its range");
    return 0;
}
