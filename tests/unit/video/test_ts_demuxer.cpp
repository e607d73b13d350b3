// The demuxer against transport streams built packet by packet from the 13818-1 tables:
// program discovery, access units with PTS/DTS and key-frame flags, KLV in both ST 1402
// carriages, every split of the byte stream, junk, lost and duplicated packets, transport
// errors, a PID change and a restarted encoder.
#include <catch2/catch.hpp>
#include <random>

#include "demux_collector.hpp"
#include "ts_builder.hpp"
#include "video/nal.hpp"

namespace v = gimbal::video;
namespace t = gimbal::test;
using t::Bytes;

namespace {

constexpr int pmt_pid = 0x1000;
constexpr int video_pid = 0x100;
constexpr int klv_pid = 0x101;

struct Au {
    Bytes data;
    std::uint64_t pts;
    std::optional<std::uint64_t> dts;
    bool key;
};

// A stream in the shape encoders send: PAT, PMT, then per frame (PAT/PMT again before key
// frames) an unbounded video PES with PCR and random_access on key frames, and a KLV PES
// after every frame.
struct StreamBuilder {
    int video_stream_type = 0x1B;
    int video = video_pid;
    int klv = klv_pid;
    int pmt = pmt_pid;
    int pat_version = 0;
    int pmt_version = 0;
    bool sync_klv = false;
    bool bounded_video = false;
    int cc_pat = 0, cc_pmt = 0, cc_video = 0, cc_klv = 0;
    std::vector<Bytes> packets;

    void psi() {
        packets.push_back(t::psi_packet(0, t::pat(1, pmt, pat_version), cc_pat));
        cc_pat = (cc_pat + 1) & 15;
        std::vector<t::EsEntry> es = {{video_stream_type, video, {}}};
        if (sync_klv) {
            es.push_back({0x15, klv, t::klva_metadata_descriptor});
        } else {
            es.push_back({0x06, klv, t::klva_registration});
        }
        packets.push_back(t::psi_packet(pmt, t::pmt(1, video, es, pmt_version), cc_pmt));
        cc_pmt = (cc_pmt + 1) & 15;
    }
    void frame(const Au& au) {
        if (au.key || packets.empty()) psi();
        const Bytes p = t::pes(0xE0, au.data, au.pts, au.dts, bounded_video);
        for (Bytes& pk :
             t::pes_packets(video, p, cc_video,
                            t::PacketOptions().pcr(au.dts.value_or(au.pts) - 9000).rai(au.key)))
            packets.push_back(std::move(pk));
    }
    void klv_set(const Bytes& set, std::uint64_t pts) {
        Bytes payload = set;
        int stream_id = 0xBD;
        if (sync_klv) {  // one complete metadata AU cell (Table 2-99)
            payload = {0x00, 0x00, 0xDF, static_cast<std::uint8_t>(set.size() >> 8),
                       static_cast<std::uint8_t>(set.size() & 0xFF)};
            t::put(payload, set);
            stream_id = 0xFC;
        }
        for (Bytes& pk : t::pes_packets(klv, t::pes(stream_id, payload, pts), cc_klv))
            packets.push_back(std::move(pk));
    }
    Bytes bytes() const { return t::join(packets); }
};

std::vector<Au> frames(int n, std::uint64_t pts0 = 900000, std::size_t size = 700) {
    std::vector<Au> out;
    for (int i = 0; i < n; ++i) {
        const bool key = i % 4 == 0;
        const std::uint64_t pts = pts0 + static_cast<std::uint64_t>(i) * 3003;
        out.push_back({t::h264_au(key, size + static_cast<std::size_t>(i) * 37,
                                  static_cast<std::uint8_t>(0x10 + i)),
                       pts + 3003, pts, key});
    }
    return out;
}

Bytes build(StreamBuilder& sb, const std::vector<Au>& aus) {
    for (std::size_t i = 0; i < aus.size(); ++i) {
        sb.frame(aus[i]);
        sb.klv_set(t::klv_packet(static_cast<std::uint8_t>(i)), aus[i].pts);
    }
    return sb.bytes();
}

void check_units(const t::Collector& c, const std::vector<Au>& aus,
                 v::Codec codec = v::Codec::h264) {
    REQUIRE(c.units.size() == aus.size());
    for (std::size_t i = 0; i < aus.size(); ++i) {
        CAPTURE(i);
        CHECK(c.units[i].codec == codec);
        CHECK(c.units[i].data == aus[i].data);
        CHECK(c.units[i].pts == aus[i].pts);
        CHECK(c.units[i].dts == aus[i].dts);
        CHECK(c.units[i].key_frame == aus[i].key);
    }
}

}  // namespace

TEST_CASE("Demux: program, access units, async KLV, PCR", "[video][demux]") {
    StreamBuilder sb;
    const auto aus = frames(6);
    const Bytes stream = build(sb, aus);
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(stream);
    // Unbounded video PES, each ended by its stuffed last packet: all out without a flush.
    CHECK(c.units.size() == aus.size());
    d.flush();
    check_units(c, aus);
    REQUIRE(c.programs.size() == 1);
    CHECK(c.programs[0].codec == v::Codec::h264);
    CHECK(c.programs[0].video_pid == video_pid);
    CHECK(c.programs[0].klv == v::KlvCarriage::async);
    CHECK(c.programs[0].klv_pid == klv_pid);
    CHECK(c.programs[0].pcr_pid == video_pid);
    REQUIRE(c.klv.size() == aus.size());
    for (std::size_t i = 0; i < aus.size(); ++i) {
        CHECK(c.klv[i].carriage == v::KlvCarriage::async);
        CHECK(c.klv[i].pts == aus[i].pts);
        CHECK(c.klv[i].data == t::klv_packet(static_cast<std::uint8_t>(i)));
    }
    CHECK(d.last_pcr() == (*aus.back().dts - 9000) * 300);
    const auto& s = d.stats();
    CHECK(s.packets * 188 == stream.size());
    CHECK(s.junk_bytes == 0);
    CHECK(s.cc_errors == 0);
    CHECK(s.dropped_units == 0);
    CHECK(s.access_units == aus.size());
    CHECK(s.klv_units == aus.size());
    CHECK(d.pending_bytes() == 0);
}

TEST_CASE("Demux: a bounded video PES is delivered without waiting for the next",
          "[video][demux]") {
    StreamBuilder sb;
    sb.bounded_video = true;
    const auto aus = frames(3);
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(build(sb, aus));
    check_units(c, aus);
}

TEST_CASE("Demux: an unbounded PES ends at stuffing, not at a PCR, else at the next start",
          "[video][demux]") {
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    Bytes s = t::psi_packet(0, t::pat(1, pmt_pid));
    t::put(s, t::psi_packet(pmt_pid, t::pmt(1, video_pid, {{0x1B, video_pid, {}}})));
    d.push(s);
    // 14-byte PES header + 354 bytes = two full packets: no stuffing anywhere.
    const Bytes exact = t::h264_au(false, 354 - 12);
    REQUIRE(exact.size() == 354);
    int cc = 0;
    d.push(t::join(t::pes_packets(video_pid, t::pes(0xE0, exact, 1000, std::nullopt, false), cc)));
    CHECK(c.units.empty());  // could go on: waits for the next start
    // The next PES: its middle packet has a PCR (an adaptation field without stuffing).
    const Bytes next = t::h264_au(false, 400, 0x66);  // PES of 426 bytes: 184 + 176 + 66
    const Bytes pes = t::pes(0xE0, next, 4000, std::nullopt, false);
    d.push(t::packet(video_pid, Bytes(pes.begin(), pes.begin() + 184),
                     t::PacketOptions().start().counter(cc)));
    REQUIRE(c.units.size() == 1);
    CHECK(c.units[0].data == exact);
    d.push(t::packet(video_pid, Bytes(pes.begin() + 184, pes.begin() + 360),
                     t::PacketOptions().counter(cc + 1).pcr(500)));
    CHECK(c.units.size() == 1);
    d.push(t::packet(video_pid, Bytes(pes.begin() + 360, pes.end()),
                     t::PacketOptions().counter(cc + 2)));
    REQUIRE(c.units.size() == 2);  // stuffed: done
    CHECK(c.units[1].data == next);
    CHECK(c.units[1].pts == 4000u);
}

TEST_CASE("Demux: every split of the byte stream gives the same units", "[video][demux]") {
    StreamBuilder sb;
    const auto aus = frames(3, 100, 300);
    const Bytes stream = build(sb, aus);
    for (std::size_t cut = 0; cut <= stream.size(); ++cut) {
        t::Collector c;
        v::TsDemuxer d(c.handlers());
        d.push(std::span(stream).first(cut));
        d.push(std::span(stream).subspan(cut));
        d.flush();
        if (c.units.size() != aus.size() || c.klv.size() != aus.size()) FAIL("split at " << cut);
        check_units(c, aus);
    }
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    for (const std::uint8_t b : stream) d.push(std::span(&b, 1));
    d.flush();
    check_units(c, aus);
    CHECK(c.klv.size() == aus.size());
}

TEST_CASE("Demux: junk between packets is skipped and counted", "[video][demux]") {
    StreamBuilder sb;
    const auto aus = frames(8);
    build(sb, aus);
    std::mt19937 rng(7);
    Bytes stream;
    std::uint64_t junk = 0;
    for (std::size_t i = 0; i < sb.packets.size(); ++i) {
        if (i % 5 == 3) {
            // Junk with sync bytes in it (none 188 bytes before the next packet: that would
            // be a packet).
            const std::size_t n = 1 + rng() % 300;
            for (std::size_t k = 0; k < n; ++k) {
                const auto b = static_cast<std::uint8_t>(k % 3 == 0 ? 0x47 : rng() % 256);
                stream.push_back(b == 0x47 && k + 188 <= n ? 0x00 : b);
            }
            junk += n;
        }
        t::put(stream, sb.packets[i]);
    }
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    // In datagram-sized pieces.
    for (std::size_t at = 0; at < stream.size(); at += 1316)
        d.push(std::span(stream).subspan(at, std::min<std::size_t>(1316, stream.size() - at)));
    d.flush();
    check_units(c, aus);
    CHECK(c.klv.size() == aus.size());
    CHECK(d.stats().junk_bytes == junk);
    CHECK(d.stats().packets == sb.packets.size());
    CHECK(d.stats().dropped_units == 0);
}

TEST_CASE("Demux: a lost packet drops only its access unit", "[video][demux]") {
    StreamBuilder sb;
    const auto aus = frames(6);
    build(sb, aus);
    // The third packet of frame 2's PES (PAT/PMT, PES of 0, KLV 0, PES of 1, ...): find the
    // video packets with payload_unit_start and remove the one after frame 2's start.
    int starts = 0;
    std::size_t victim = 0;
    for (std::size_t i = 0; i < sb.packets.size(); ++i) {
        const Bytes& p = sb.packets[i];
        const int pid = ((p[1] & 0x1F) << 8) | p[2];
        if (pid == video_pid && (p[1] & 0x40) && ++starts == 3) {
            victim = i + 2;
            break;
        }
    }
    REQUIRE(victim > 0);
    sb.packets.erase(sb.packets.begin() + static_cast<long>(victim));
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(sb.bytes());
    d.flush();
    std::vector<Au> expected = aus;
    expected.erase(expected.begin() + 2);
    check_units(c, expected);
    CHECK(d.stats().cc_errors == 1);
    CHECK(d.stats().dropped_units == 1);
    CHECK(c.klv.size() == aus.size());
}

TEST_CASE("Demux: duplicates, discontinuity indicator and transport errors", "[video][demux]") {
    StreamBuilder sb;
    const auto aus = frames(4);
    build(sb, aus);
    std::vector<Bytes> packets = sb.packets;
    // Duplicate the packet after frame 1's start: allowed once (2.4.3.3), ignored.
    std::size_t dup = 0;
    int starts = 0;
    for (std::size_t i = 0; i < packets.size(); ++i) {
        const int pid = ((packets[i][1] & 0x1F) << 8) | packets[i][2];
        if (pid == video_pid && (packets[i][1] & 0x40) && ++starts == 2) dup = i + 1;
    }
    packets.insert(packets.begin() + static_cast<long>(dup), packets[dup]);
    {
        t::Collector c;
        v::TsDemuxer d(c.handlers());
        d.push(t::join(packets));
        d.flush();
        check_units(c, aus);
        CHECK(d.stats().cc_errors == 0);
    }
    // A transport error in frame 3's PES: counted, the unit dropped (the gap it leaves).
    std::vector<Bytes> bad = sb.packets;
    std::size_t last_start = 0;
    for (std::size_t i = 0; i < bad.size(); ++i) {
        const int pid = ((bad[i][1] & 0x1F) << 8) | bad[i][2];
        if (pid == video_pid && (bad[i][1] & 0x40)) last_start = i;
    }
    bad[last_start + 1][1] |= 0x80;
    {
        t::Collector c;
        v::TsDemuxer d(c.handlers());
        d.push(t::join(bad));
        d.flush();
        check_units(c, std::vector<Au>(aus.begin(), aus.end() - 1));
        CHECK(d.stats().transport_errors == 1);
        CHECK(d.stats().dropped_units == 1);
    }
    // A counter jump flagged by discontinuity_indicator is not an error.
    StreamBuilder jump;
    const auto first = frames(2);
    build(jump, first);
    jump.cc_video = 9;
    const Au next{t::h264_au(false, 300), 990000, std::nullopt, false};
    Bytes p = t::pes(0xE0, next.data, next.pts, std::nullopt, false);
    auto pk = t::pes_packets(video_pid, p, jump.cc_video, t::PacketOptions().pcr(980000).disc());
    for (Bytes& x : pk) jump.packets.push_back(std::move(x));
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(jump.bytes());
    d.flush();
    CHECK(c.units.size() == 3);
    CHECK(d.stats().cc_errors == 0);
}

TEST_CASE("Demux: PMT moves the video and KLV PIDs", "[video][demux]") {
    StreamBuilder sb;
    const auto before = frames(3);
    build(sb, before);
    sb.video = 0x200;
    sb.klv = 0x201;
    sb.pmt_version = 1;
    const auto after = frames(3, 2'000'000);
    for (std::size_t i = 0; i < after.size(); ++i) {
        sb.frame(after[i]);
        sb.klv_set(t::klv_packet(0xA0), after[i].pts);
    }
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(sb.bytes());
    d.flush();
    std::vector<Au> all = before;
    all.insert(all.end(), after.begin(), after.end());
    check_units(c, all);
    CHECK(c.klv.size() == 6);
    REQUIRE(c.programs.size() == 2);
    CHECK(c.programs[1].video_pid == 0x200);
    CHECK(c.programs[1].klv_pid == 0x201);
    CHECK(d.stats().program_changes == 1);
    CHECK(d.program()->video_pid == 0x200);
}

TEST_CASE("Demux: a restarted encoder (new PAT, PMT PID, codec, counters, PTS)", "[video][demux]") {
    StreamBuilder sb;
    const auto before = frames(5);
    build(sb, before);
    // The encoder dies while sending the next frame: half its packets go out.
    int cc = sb.cc_video;
    auto half = t::pes_packets(video_pid, t::pes(0xE0, t::h264_au(false, 2000), 2'000'000), cc);
    half.resize(half.size() / 2);
    // It restarts: PAT version 1, another PMT PID, H.265 on PID 0x300, counters from 0,
    // PTS near zero.
    StreamBuilder restarted;
    restarted.pat_version = 1;
    restarted.pmt = 0x1100;
    restarted.video = 0x300;
    restarted.klv = 0x301;
    restarted.video_stream_type = 0x24;
    std::vector<Au> hevc;
    for (int i = 0; i < 3; ++i) {
        Bytes au = {0,    0,   1, 0x46, 0x01,
                    0x50, 0,   0, 1,    static_cast<std::uint8_t>(i == 0 ? 0x26 : 0x02),
                    0x01, 0xAF};
        au.insert(au.end(), 400, static_cast<std::uint8_t>(i + 1));
        hevc.push_back({au, 3000u + static_cast<std::uint64_t>(i) * 3000, std::nullopt, i == 0});
    }
    build(restarted, hevc);
    // The receiver joined late: the first bytes are the middle of the first packet (PAT),
    // so the PMT that follows means nothing until the PAT comes again before frame 4.
    Bytes stream = sb.bytes();
    stream.erase(stream.begin(), stream.begin() + 100);
    t::put(stream, t::join(half));
    const Bytes tail = restarted.bytes();
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(stream);
    d.push(tail);
    d.flush();
    // Frame 4, the half frame the dying encoder sent (its PES ends with the program), then
    // the restarted encoder's H.265.
    REQUIRE(c.units.size() == 2 + hevc.size());
    CHECK(c.units[0].data == before[4].data);
    CHECK(c.units[0].pts == before[4].pts);
    CHECK(c.units[1].pts == 2'000'000u);
    for (std::size_t i = 0; i < hevc.size(); ++i) {
        const auto& u = c.units[2 + i];
        CHECK(u.codec == v::Codec::h265);
        CHECK(u.data == hevc[i].data);
        CHECK(u.pts == hevc[i].pts);
        CHECK(u.key_frame == hevc[i].key);
    }
    CHECK(c.programs.back().codec == v::Codec::h265);
    CHECK(c.programs.back().pmt_pid == 0x1100);
    CHECK(d.stats().junk_bytes == 88);
    CHECK(d.stats().program_changes == 1);
    CHECK(c.klv.size() == 1 + hevc.size());
}

TEST_CASE("Demux: synchronous KLV (metadata stream, AU cells, fragments)", "[video][demux]") {
    StreamBuilder sb;
    sb.sync_klv = true;
    const auto aus = frames(3);
    build(sb, aus);
    // One PES with a set split over two cells: first (10) and last (01) fragments.
    const Bytes big = t::klv_packet(0xEE, 300);
    Bytes cells = {0x00, 0x01, 0x9F, 0x00, 0x64};
    cells.insert(cells.end(), big.begin(), big.begin() + 100);
    t::put(cells, {0x00, 0x01, 0x5F, static_cast<int>((big.size() - 100) >> 8),
                   static_cast<int>((big.size() - 100) & 0xFF)});
    cells.insert(cells.end(), big.begin() + 100, big.end());
    for (Bytes& pk : t::pes_packets(klv_pid, t::pes(0xFC, cells, 5'000'000), sb.cc_klv))
        sb.packets.push_back(std::move(pk));
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(sb.bytes());
    d.flush();
    check_units(c, aus);
    REQUIRE(c.programs.size() == 1);
    CHECK(c.programs[0].klv == v::KlvCarriage::sync);
    REQUIRE(c.klv.size() == aus.size() + 1);
    for (std::size_t i = 0; i < aus.size(); ++i) {
        CHECK(c.klv[i].carriage == v::KlvCarriage::sync);
        CHECK(c.klv[i].pts == aus[i].pts);
        CHECK(c.klv[i].data == t::klv_packet(static_cast<std::uint8_t>(i)));
    }
    CHECK(c.klv.back().data == big);
    CHECK(c.klv.back().pts == 5'000'000u);
}

TEST_CASE("Demux: streams it does not follow and broken PSI", "[video][demux]") {
    // A PMT whose private stream has no KLVA registration: no KLV is reported.
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    int cc = 0;
    Bytes s = t::psi_packet(0, t::pat(1, pmt_pid));
    t::put(s, t::psi_packet(pmt_pid,
                            t::pmt(1, video_pid, {{0x1B, video_pid, {}}, {0x06, klv_pid, {}}})));
    for (Bytes& p : t::pes_packets(klv_pid, t::pes(0xBD, t::klv_packet(1), 0), cc)) t::put(s, p);
    // A PAT with a bad CRC is counted and changes nothing.
    Bytes bad = t::pat(1, 0x0777, 1);
    bad.back() ^= 0xFF;
    t::put(s, t::psi_packet(0, bad, 1));
    d.push(s);
    REQUIRE(d.program());
    CHECK_FALSE(d.program()->klv);
    CHECK(d.program()->pmt_pid == pmt_pid);
    CHECK(c.klv.empty());
    CHECK(d.stats().psi_errors == 1);
}

TEST_CASE("Demux: a PES that never ends is dropped at its bound", "[video][demux]") {
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    Bytes s = t::psi_packet(0, t::pat(1, pmt_pid));
    t::put(s, t::psi_packet(pmt_pid, t::pmt(1, video_pid, {{0x1B, video_pid, {}}})));
    d.push(s);
    int cc = 0;
    const Bytes start = t::pes(0xE0, Bytes(184 - 14, 0x11), 1000, std::nullopt, false);
    d.push(t::packet(video_pid, start, t::PacketOptions().start().counter(cc)));
    const Bytes filler(184, 0x22);
    for (std::size_t i = 0; i < v::max_access_unit_bytes / 184 + 10; ++i) {
        cc = (cc + 1) & 15;
        d.push(t::packet(video_pid, filler, t::PacketOptions().counter(cc)));
    }
    CHECK(d.stats().oversized_units == 1);
    CHECK(d.stats().pes_errors == 0);
    CHECK(c.units.empty());
    // The next unit is read normally.
    cc = (cc + 1) & 15;
    for (Bytes& p : t::pes_packets(video_pid, t::pes(0xE0, t::h264_au(true), 5000), cc)) d.push(p);
    REQUIRE(c.units.size() == 1);
    CHECK(c.units[0].pts == 5000u);
}

TEST_CASE("Demux: middle fragments of a metadata AU without end are dropped at 64 KiB",
          "[video][demux]") {
    // ST 1402 synchronous KLV: a first fragment, then "middle" cells forever (issue 25: 402 MiB
    // of them kept 461 MB). The AU being joined stays under max_metadata_au_bytes; the next
    // whole set is read normally.
    StreamBuilder sb;
    sb.sync_klv = true;
    build(sb, frames(1));
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(sb.bytes());
    const std::size_t before = c.klv.size();
    const auto cell = [](int fragment, std::size_t size, std::uint8_t fill) {
        Bytes b = {0x00, 0x01, static_cast<std::uint8_t>((fragment << 6) | 0x1F),
                   static_cast<std::uint8_t>(size >> 8), static_cast<std::uint8_t>(size & 0xFF)};
        b.insert(b.end(), size, fill);
        return b;
    };
    const auto send_pes = [&](const Bytes& cells) {
        Bytes s;
        for (Bytes& pk : t::pes_packets(klv_pid, t::pes(0xFC, cells, 7'000'000), sb.cc_klv))
            t::put(s, pk);
        d.push(s);
    };
    send_pes(cell(2, 60'000, 0xA1));                                // first
    for (int i = 0; i < 200; ++i) send_pes(cell(0, 60'000, 0xA2));  // 12 MB of middles
    CHECK(d.stats().metadata_dropped >= 199);
    CHECK(c.klv.size() == before);
    // A whole set after it is delivered.
    const Bytes set = t::klv_packet(0x42);
    Bytes whole = cell(3, 0, 0);
    whole[3] = 0;
    whole[4] = static_cast<std::uint8_t>(set.size());
    t::put(whole, set);
    send_pes(whole);
    REQUIRE(c.klv.size() == before + 1);
    CHECK(c.klv.back().data == set);
    // An AU of exactly 64 KiB in two fragments still comes through.
    const std::size_t half = v::max_metadata_au_bytes / 2;
    send_pes(cell(2, half, 0xB1));
    send_pes(cell(1, half, 0xB2));
    REQUIRE(c.klv.size() == before + 2);
    CHECK(c.klv.back().data.size() == v::max_metadata_au_bytes);
}

TEST_CASE("Demux: a KLV PES without end is dropped at its bound", "[video][demux]") {
    StreamBuilder sb;
    build(sb, frames(1));
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(sb.bytes());
    const auto errors = d.stats().oversized_klv;
    // An unbounded KLV PES (length 0) that never ends.
    int cc = sb.cc_klv;
    d.push(t::packet(klv_pid, t::pes(0xBD, Bytes(170, 0x11), 1000, std::nullopt, false),
                     t::PacketOptions().start().counter(cc)));
    const Bytes filler(184, 0x22);
    for (std::size_t i = 0; i < v::max_klv_pes_bytes / 184 + 10; ++i) {
        cc = (cc + 1) & 15;
        d.push(t::packet(klv_pid, filler, t::PacketOptions().counter(cc)));
    }
    CHECK(d.stats().oversized_klv == errors + 1);
}
