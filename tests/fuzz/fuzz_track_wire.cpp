// libFuzzer target for the gimbald <-> gimbal-track messages (lib/track/wire): the input is a
// sequence of datagrams, each a u16 little-endian length and its bytes. Every datagram is
// decoded; one that decodes must encode back to exactly its bytes (the format has one
// spelling per message), and access units go through the assembler, whose whole units must
// have their declared size.
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "track/wire/assembler.hpp"
#include "track/wire/codec.hpp"

namespace w = gimbal::track::wire;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_track_wire: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    w::AccessUnitAssembler assembler;
    std::vector<std::uint8_t> again;
    std::size_t at = 0;
    while (at + 2 <= size) {
        const std::size_t n = std::min<std::size_t>(
            static_cast<std::size_t>(data[at] | (data[at + 1] << 8)), size - at - 2);
        const std::span<const std::uint8_t> datagram(data + at + 2, n);
        at += 2 + n;
        (void)w::peek_type(datagram);
        const auto decoded = w::decode(datagram);
        if (!decoded.message) {
            if (decoded.error.empty()) fail("refused without a reason");
            continue;
        }
        std::string error;
        if (!w::encode(*decoded.message, again, &error)) fail("a decoded message does not encode");
        if (again.size() != datagram.size() ||
            !std::equal(again.begin(), again.end(), datagram.begin()))
            fail("re-encoding changed the bytes");
        if (const auto* piece = std::get_if<w::AccessUnit>(&*decoded.message)) {
            if (piece->bytes.data() < datagram.data() ||
                piece->bytes.data() + piece->bytes.size() > datagram.data() + datagram.size())
                fail("access unit bytes outside the datagram");
            if (const auto unit = assembler.add(*piece)) {
                if (unit->bytes.size() != piece->total_bytes) fail("a whole unit of another size");
                if (unit->pts_90k != piece->pts_90k) fail("a whole unit with another time");
            }
        }
    }
    return 0;
}
