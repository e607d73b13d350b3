// The muxer: its PAT/PMT packets byte for byte against hand-built ones, the timing rules
// (PSI every psi_interval and before key frames, PCR on the video PID at most 100 ms apart
// and never ahead of the DTS), continuity counters, stuffing and UDP-sized chunks, and a
// round trip through the demuxer.
#include <catch2/catch.hpp>
#include <map>

#include "demux_collector.hpp"
#include "ts_builder.hpp"
#include "video/ts_muxer.hpp"
#include "video/ts_packet.hpp"

namespace v = gimbal::video;
namespace t = gimbal::test;
using t::Bytes;

namespace {

struct Output {
    std::vector<Bytes> chunks;
    Bytes all() const { return t::join(chunks); }
    std::vector<Bytes> packets() const {
        std::vector<Bytes> out;
        const Bytes a = all();
        for (std::size_t i = 0; i + 188 <= a.size(); i += 188)
            out.emplace_back(a.begin() + static_cast<long>(i),
                             a.begin() + static_cast<long>(i + 188));
        return out;
    }
};

v::TsMuxer make(Output& out, v::MuxerOptions o = {}) {
    return v::TsMuxer(o, v::Codec::h264, [&out](std::span<const std::uint8_t> c) {
        out.chunks.emplace_back(c.begin(), c.end());
    });
}

v::AccessUnitBuffer unit(int i, std::size_t size = 5000, int gop = 30) {
    v::AccessUnitBuffer au;
    au.key_frame = i % gop == 0;
    au.data = t::h264_au(au.key_frame, size, static_cast<std::uint8_t>(i));
    au.dts = 1'000'000 + static_cast<std::uint64_t>(i) * 3000;  // 30 fps
    au.pts = *au.dts + 6000;
    return au;
}

}  // namespace

TEST_CASE("Mux: PAT and PMT packets are the hand-built ones", "[video][mux]") {
    Output out;
    auto mux = make(out);
    mux.write_video(unit(0).view());
    const auto packets = out.packets();
    REQUIRE(packets.size() > 3);
    CHECK(packets[0] == t::psi_packet(0x0000, t::pat(1, 0x1000)));
    CHECK(packets[1] ==
          t::psi_packet(
              0x1000, t::pmt(1, 0x100, {{0x1B, 0x100, {}}, {0x06, 0x101, t::klva_registration}})));
    // The first video packet: PUSI, adaptation field with random_access and PCR = DTS - 100 ms.
    const auto first = v::parse_ts_packet(packets[2]);
    REQUIRE(first);
    CHECK(first->pid == 0x100);
    CHECK(first->payload_unit_start);
    CHECK(first->random_access);
    CHECK(first->pcr == (1'000'000u - 9000u) * 300u);
    // H.265 and no KLV stream: the PMT says so.
    Output out2;
    v::MuxerOptions o;
    o.klv = false;
    v::TsMuxer hevc(o, v::Codec::h265, [&](std::span<const std::uint8_t> c) {
        out2.chunks.emplace_back(c.begin(), c.end());
    });
    auto au = unit(0);
    au.codec = v::Codec::h265;
    hevc.write_video(au.view());
    CHECK(out2.packets()[1] == t::psi_packet(0x1000, t::pmt(1, 0x100, {{0x24, 0x100, {}}})));
}

TEST_CASE("Mux: chunks, counters, PSI and PCR timing over 10 s of 30 fps", "[video][mux]") {
    Output out;
    auto mux = make(out);
    std::vector<v::AccessUnitBuffer> units;
    for (int i = 0; i < 300; ++i) {
        units.push_back(unit(i, 1000 + static_cast<std::size_t>(i * 97 % 9000)));
        mux.write_video(units.back().view());
        if (i % 3 == 0)
            mux.write_klv(t::klv_packet(static_cast<std::uint8_t>(i)), units.back().pts);
    }
    // Chunks: whole packets, at most 7; the only short ones end a unit.
    for (const Bytes& c : out.chunks) {
        CHECK(c.size() % 188 == 0);
        CHECK(c.size() <= 1316);
        CHECK(!c.empty());
    }
    CHECK(mux.stats().chunks == out.chunks.size());
    std::map<int, int> cc;
    std::optional<std::uint64_t> last_pat_time;
    std::uint64_t last_pcr = 0;
    bool pcr_seen = false;
    std::uint64_t clock = 0;  // DTS of the unit being written
    std::size_t unit_index = 0;
    bool psi_since_last_unit = false;
    for (const Bytes& p : out.packets()) {
        const auto tp = v::parse_ts_packet(p);
        REQUIRE(tp);
        if (tp->has_payload) {
            if (cc.count(tp->pid)) CHECK(tp->continuity_counter == ((cc[tp->pid] + 1) & 15));
            cc[tp->pid] = tp->continuity_counter;
        }
        if (tp->pid == 0) psi_since_last_unit = true;
        if (tp->pcr) {
            CHECK(tp->pid == 0x100);
            if (pcr_seen) {
                CHECK(*tp->pcr >= last_pcr);
                CHECK(*tp->pcr - last_pcr <= 100u * 27'000);
            }
            last_pcr = *tp->pcr;
            pcr_seen = true;
        }
        if (tp->pid == 0x100 && tp->payload_unit_start) {
            REQUIRE(unit_index < units.size());
            const auto& u = units[unit_index++];
            clock = *u.dts;
            REQUIRE(tp->pcr);
            CHECK(*tp->pcr <= *u.dts * 300);
            if (u.key_frame) CHECK(psi_since_last_unit);  // PAT/PMT right before key frames
            if (psi_since_last_unit) {                    // PSI at most 500 ms apart in stream time
                if (last_pat_time) CHECK(clock - *last_pat_time <= 45'000);
                last_pat_time = clock;
            }
            CHECK(tp->random_access == u.key_frame);
            psi_since_last_unit = false;
        }
    }
    CHECK(unit_index == units.size());
    CHECK(mux.stats().psi_repeats >= 10 * 2);

    // And the demuxer reads back exactly what went in.
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    for (const Bytes& chunk : out.chunks) d.push(chunk);
    REQUIRE(c.units.size() == units.size());  // bounded PES: no flush needed
    for (std::size_t i = 0; i < units.size(); ++i) CHECK(t::same_unit(c.units[i], units[i]));
    REQUIRE(c.klv.size() == 100);
    CHECK(c.klv[1].data == t::klv_packet(3));
    CHECK(c.klv[1].pts == units[3].pts);
    CHECK(c.klv[1].carriage == v::KlvCarriage::async);
    CHECK(d.stats().cc_errors == 0);
    CHECK(d.stats().junk_bytes == 0);
}

TEST_CASE("Mux: KLV alone keeps a PCR going; large and bad units", "[video][mux]") {
    Output out;
    auto mux = make(out);
    mux.write_video(unit(0).view());
    // Video stalls; KLV goes on at 10 Hz for a second: PCR-only packets every 100 ms.
    const std::uint64_t base = *unit(0).pts;
    for (int i = 1; i <= 10; ++i)
        mux.write_klv(t::klv_packet(1), base + static_cast<std::uint64_t>(i) * 9000);
    int pcrs = 0;
    for (const Bytes& p : out.packets()) {
        const auto tp = v::parse_ts_packet(p);
        if (tp->pcr) {
            ++pcrs;
            CHECK(tp->pid == 0x100);
        }
    }
    CHECK(pcrs == 11);
    // A unit over 64 KiB: unbounded video PES, read back when the next one starts.
    Output big_out;
    auto big_mux = make(big_out);
    auto big = unit(0, 200'000);
    big_mux.write_video(big.view());
    big_mux.write_video(unit(1).view());
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(big_out.all());
    REQUIRE(c.units.size() == 2);
    CHECK(t::same_unit(c.units[0], big));
    // Refused: empty units and KLV too long for a bounded PES.
    big_mux.write_video(v::AccessUnit{});
    big_mux.write_klv(Bytes(70'000, 1), std::nullopt);
    CHECK(big_mux.stats().rejected == 2);
}

TEST_CASE("Mux: a unit without timestamps still goes out, PSI by packet count", "[video][mux]") {
    Output out;
    auto mux = make(out);
    auto au = unit(0);
    au.pts.reset();
    au.dts.reset();
    for (int i = 0; i < 50; ++i) mux.write_video(au.view());
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(out.all());
    CHECK(c.units.size() == 50);
    CHECK_FALSE(c.units[0].pts);
    CHECK(mux.stats().psi_repeats >= 50);  // every unit is a key frame here
}

TEST_CASE("Mux: a restarted input (PTS back to zero, new codec) is flagged and announced",
          "[video][mux]") {
    Output out;
    auto mux = make(out);
    for (int i = 0; i < 5; ++i) mux.write_video(unit(i).view());
    // The encoder restarts as H.265 with timestamps near zero.
    v::AccessUnitBuffer again = unit(0);
    again.codec = v::Codec::h265;
    again.dts = 3000;
    again.pts = 9000;
    const std::size_t before = out.packets().size();
    mux.write_video(again.view());
    const auto packets = out.packets();
    bool pmt_h265 = false;
    bool discontinuity = false;
    for (std::size_t i = before; i < packets.size(); ++i) {
        if (packets[i] ==
            t::psi_packet(
                0x1000,
                t::pmt(1, 0x100, {{0x24, 0x100, {}}, {0x06, 0x101, t::klva_registration}}, 1),
                static_cast<int>((packets[i][3] & 0x0F))))
            pmt_h265 = true;
        const auto tp = v::parse_ts_packet(packets[i]);
        if (tp->pid == 0x100 && tp->payload_unit_start) {
            discontinuity = tp->discontinuity;
            CHECK(tp->pcr == (3000u + v::pts_modulus - 9000u) % v::pts_modulus * 300u);
        }
    }
    CHECK(pmt_h265);       // PMT version 1 says H.265
    CHECK(discontinuity);  // the PCR went back: discontinuity_indicator
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(out.all());
    REQUIRE(c.units.size() == 6);
    CHECK(c.units.back().codec == v::Codec::h265);
    CHECK(d.stats().program_changes == 1);
}
