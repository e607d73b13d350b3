// libFuzzer target for lib/video's MPEG-TS demuxer: the input pushed in chunks whose sizes
// come from the input itself (so splits are explored too), then every access unit and KLV
// unit it delivers muxed again and demuxed a second time, which must give them back.
// Invariants: every byte is accounted for (packets, junk, pending); the round trip is exact.
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "video/ts_demuxer.hpp"
#include "video/ts_muxer.hpp"

namespace v = gimbal::video;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_ts_demux: %s\n", what);
    std::abort();
}

struct Klv {
    std::optional<std::uint64_t> pts;
    std::vector<std::uint8_t> data;
};

struct Seen {
    std::vector<v::AccessUnitBuffer> units;
    std::vector<Klv> klv;
    v::TsDemuxer::Handlers handlers() {
        return {[this](const v::AccessUnit& au) { units.emplace_back(au); },
                [this](const v::KlvUnit& k) {
                    klv.push_back({k.pts, {k.data.begin(), k.data.end()}});
                },
                {}};
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> input(data, size);
    Seen first;
    v::TsDemuxer demux(first.handlers());
    for (std::size_t i = 0; i < input.size();) {
        const std::size_t n = std::min<std::size_t>(1 + input[i] * 7u % 1400u, input.size() - i);
        demux.push(input.subspan(i, n));
        i += n;
    }
    const auto& s = demux.stats();
    if (s.bytes != size) fail("bytes pushed not counted");
    if (s.packets * 188 + s.junk_bytes + demux.pending_bytes() != s.bytes)
        fail("bytes neither packets, junk nor pending");
    demux.flush();

    // Round trip of what came out (empty units and over-long KLV are refused by the muxer).
    std::vector<v::AccessUnitBuffer> units;
    std::vector<Klv> klv;
    for (auto& u : first.units)
        if (!u.data.empty()) units.push_back(u);
    for (auto& k : first.klv)
        if (!k.data.empty() && k.data.size() <= 65000) klv.push_back(k);
    std::vector<std::uint8_t> ts;
    v::TsMuxer mux(
        {}, units.empty() ? v::Codec::h264 : units[0].codec,
        [&](std::span<const std::uint8_t> c) { ts.insert(ts.end(), c.begin(), c.end()); });
    for (const auto& u : units) mux.write_video(u.view());
    for (const auto& k : klv) mux.write_klv(k.data, k.pts);
    Seen second;
    v::TsDemuxer again(second.handlers());
    again.push(ts);
    again.flush();
    if (second.units.size() != units.size()) fail("round trip lost access units");
    for (std::size_t i = 0; i < units.size(); ++i) {
        const auto& a = units[i];
        const auto& b = second.units[i];
        if (a.data != b.data || a.codec != b.codec || a.key_frame != b.key_frame ||
            a.pts != b.pts ||
            a.dts.value_or(a.pts.value_or(0)) != b.dts.value_or(b.pts.value_or(0)))
            fail("round trip changed an access unit");
    }
    if (second.klv.size() != klv.size()) fail("round trip lost KLV units");
    for (std::size_t i = 0; i < klv.size(); ++i) {
        if (second.klv[i].data != klv[i].data || second.klv[i].pts != klv[i].pts)
            fail("round trip changed a KLV unit");
    }
    if (again.stats().cc_errors != 0 || again.stats().junk_bytes != 0)
        fail("the muxer's own stream has errors");
    return 0;
}
