// libFuzzer target for the MAVLink codec: the framer fed the input whole, in chunks and as one
// UDP datagram (with and without accepting signed frames), every message re-encoded and decoded
// again, and decode_payload() on arbitrary ids and lengths. Any crash, sanitizer report or broken
// invariant aborts.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <vector>

#include "mavlink/mavlink.hpp"

namespace m = gimbal::mavlink;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_mavlink: %s\n", what);
    std::abort();
}

void check_accounting(const m::Framer& f) {
    const auto& s = f.stats();
    if (s.bytes != s.frame_bytes + s.skipped_bytes + s.dropped_bytes + f.pending_bytes())
        fail("framer lost track of bytes");
}

// Message equality by bytes: a NaN float is not equal to itself.
bool same(const m::Message& x, const m::Message& y) {
    if (x.version != y.version || x.seq != y.seq || x.sysid != y.sysid || x.compid != y.compid ||
        x.msgid != y.msgid || x.signature != y.signature)
        return false;
    const m::PayloadBytes a = m::encode_payload(x.payload);
    const m::PayloadBytes b = m::encode_payload(y.payload);
    return std::ranges::equal(a.view(), b.view());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> input(data, size);
    for (const bool accept_signed : {false, true}) {
        m::Framer whole(m::FramerOptions{accept_signed, {}});
        const std::vector<m::Message> all = whole.push(input);
        check_accounting(whole);
        if (whole.stats().frames != all.size()) fail("frames counter differs from messages");

        m::Framer chunked(m::FramerOptions{accept_signed, {}});
        std::vector<m::Message> pieces;
        for (std::size_t i = 0; i < size;) {
            const std::size_t n = std::min<std::size_t>(1 + data[i] % 61, size - i);
            for (auto& msg : chunked.push(input.subspan(i, n))) pieces.push_back(std::move(msg));
            check_accounting(chunked);
            i += n;
        }
        if (!std::ranges::equal(pieces, all, same)) fail("chunked delivery differs from one push");

        // As one UDP datagram: parsed on its own, nothing left over for the next one.
        m::Framer datagram(m::FramerOptions{accept_signed, {}});
        const auto from_datagram = datagram.push_datagram(input);
        check_accounting(datagram);
        if (datagram.pending_bytes() != 0) fail("a datagram left bytes for the next one");
        if (datagram.stats().frames != from_datagram.size())
            fail("frames counter differs from messages (datagram)");

        for (const auto& msg : all) {
            const auto bytes = msg.version == 1
                                   ? m::encode_v1(msg.payload, msg.sysid, msg.compid, msg.seq)
                                   : m::encode_v2(msg.payload, msg.sysid, msg.compid, msg.seq);
            m::Framer again;
            const auto back = again.push(bytes);
            // Compare bytes, not values: a NaN float is not equal to itself.
            if (back.size() != 1) fail("a delivered message does not survive re-encoding");
            const m::PayloadBytes a = m::encode_payload(back[0].payload);
            const m::PayloadBytes b = m::encode_payload(msg.payload);
            if (!std::ranges::equal(a.view(), b.view()))
                fail("a delivered message does not survive re-encoding");
        }
    }
    if (size >= 1) {
        static constexpr std::uint32_t ids[] = {0,   2,   30,  33,  65,  75,  76,  77, 259, 271,
                                                280, 281, 282, 283, 284, 285, 287, 1,  255};
        (void)m::decode_payload(ids[data[0] % std::size(ids)], input.subspan(1));
    }
    // With a signing key: verification runs on every signed frame; it must not crash and a
    // frame that verifies must re-verify.
    m::SigningKey key{};
    key[0] = 1;
    m::Framer keyed(m::FramerOptions{true, key});
    for (const auto& msg : keyed.push(input))
        if (msg.signature && msg.signature->verified && msg.version != 2)
            fail("a v1 frame claims a verified signature");
    return 0;
}
