// lib/video checked by tools nobody here wrote: an H.264 stream encoded by ffmpeg/libx264
// (with B-frames, so DTS differs from PTS) in ffmpeg's own MPEG-TS is demuxed, muxed again
// with a KLV set per frame, and then
//   - ffprobe finds an h264 video stream of the right size and a `klv` data stream, with
//     one packet per access unit and per set,
//   - ffmpeg decodes the video without an error,
//   - GStreamer's tsdemux hands out the KLV as meta/x-klv, byte for byte what went in,
//   - ffmpeg's mpegts muxer re-muxes it (-c copy) and our demuxer reads that back unchanged.
// The tools are Debian packages installed by scripts/install-deps.sh.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "demux_collector.hpp"
#include "ts_builder.hpp"
#include "video/nal.hpp"
#include "video/ts_muxer.hpp"

namespace v = gimbal::video;
namespace t = gimbal::test;
namespace fs = std::filesystem;
using t::Bytes;

namespace {

struct Run {
    int status = -1;
    std::string out;
};

Run run(const std::string& command) {
    Run r;
    FILE* p = popen((command + " 2>&1").c_str(), "r");
    REQUIRE(p != nullptr);
    char buf[4096];
    std::size_t n = 0;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
    const int status = pclose(p);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

Bytes read_file(const fs::path& path) {
    std::ifstream f(path, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& path, const Bytes& b) {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

struct TempDir {
    fs::path path;
    TempDir() {
        std::string tmpl = (fs::temp_directory_path() / "gimbal-video-XXXXXX").string();
        REQUIRE(mkdtemp(tmpl.data()) != nullptr);
        path = tmpl;
    }
    ~TempDir() { fs::remove_all(path); }
};

t::Collector demux_file(const fs::path& path, v::DemuxStats* stats = nullptr) {
    t::Collector c;
    v::TsDemuxer d(c.handlers());
    d.push(read_file(path));
    d.flush();
    if (stats) *stats = d.stats();
    return c;
}

}  // namespace

TEST_CASE("Tools: ffprobe, ffmpeg and GStreamer read what the muxer writes", "[video][tools]") {
    TempDir dir;
    const fs::path input = dir.path / "x264.ts";
    const auto encode =
        run("ffmpeg -nostdin -v error -y -f lavfi -i "
            "testsrc=size=320x240:rate=25:duration=2 -pix_fmt yuv420p "
            "-c:v libx264 -g 25 -bf 2 -f mpegts " +
            input.string());
    INFO(encode.out);
    REQUIRE(encode.status == 0);

    v::DemuxStats in_stats;
    const t::Collector in = demux_file(input, &in_stats);
    REQUIRE(in.units.size() == 50);
    CHECK(in_stats.cc_errors == 0);
    CHECK(in.units[0].key_frame);
    CHECK(v::find_format(v::Codec::h264, in.units[0].data) == v::VideoFormat{320, 240, 25.0});
    const bool reordered = std::any_of(in.units.begin(), in.units.end(),
                                       [](const auto& u) { return u.dts && u.dts != u.pts; });
    CHECK(reordered);

    // Mux again with one KLV set per frame (timestamps in decode order, as a relay has them).
    Bytes out_bytes;
    Bytes klv_sent;
    {
        v::TsMuxer mux({}, v::Codec::h264, [&](std::span<const std::uint8_t> c) {
            out_bytes.insert(out_bytes.end(), c.begin(), c.end());
        });
        for (std::size_t i = 0; i < in.units.size(); ++i) {
            const auto& u = in.units[i];
            mux.write_video(u.view());
            const Bytes set = t::klv_packet(static_cast<std::uint8_t>(i), 10 + i);
            klv_sent.insert(klv_sent.end(), set.begin(), set.end());
            mux.write_klv(set, u.dts ? u.dts : u.pts);
        }
    }
    const fs::path output = dir.path / "relayed.ts";
    write_file(output, out_bytes);

    const auto probe =
        run("ffprobe -v error -count_packets -show_entries "
            "stream=codec_name,codec_type,width,height,nb_read_packets -of compact " +
            output.string());
    INFO(probe.out);
    REQUIRE(probe.status == 0);
    CHECK(probe.out.find(
              "codec_name=h264|codec_type=video|width=320|height=240|nb_read_packets=50") !=
          std::string::npos);
    CHECK(probe.out.find("codec_name=klv|codec_type=data|nb_read_packets=50") != std::string::npos);

    const auto decode = run("ffmpeg -nostdin -v error -i " + output.string() + " -f null -");
    INFO(decode.out);
    CHECK(decode.status == 0);
    CHECK(decode.out.empty());

    // tsdemux links its KLV pad only to something that accepts meta/x-klv.
    const fs::path klv_out = dir.path / "klv.bin";
    const auto gst = run("gst-launch-1.0 -q filesrc location=" + output.string() +
                         " ! tsdemux ! meta/x-klv ! filesink location=" + klv_out.string());
    INFO(gst.out);
    CHECK(gst.status == 0);
    CHECK(read_file(klv_out) == klv_sent);

    const fs::path remuxed = dir.path / "ffmpeg-remux.ts";
    const auto remux = run("ffmpeg -nostdin -v error -y -i " + output.string() +
                           " -map 0 -c copy -f mpegts " + remuxed.string());
    INFO(remux.out);
    REQUIRE(remux.status == 0);
    v::DemuxStats back_stats;
    const t::Collector back = demux_file(remuxed, &back_stats);
    REQUIRE(back.units.size() == in.units.size());
    for (std::size_t i = 0; i < back.units.size(); ++i) {
        CAPTURE(i);
        CHECK(back.units[i].data == in.units[i].data);
        CHECK(back.units[i].key_frame == in.units[i].key_frame);
        // ffmpeg starts its output clock at its own offset: differences are kept.
        CHECK(*back.units[i].pts - *back.units[0].pts == *in.units[i].pts - *in.units[0].pts);
    }
    REQUIRE(back.klv.size() == 50);
    Bytes klv_back;
    for (const auto& k : back.klv) klv_back.insert(klv_back.end(), k.data.begin(), k.data.end());
    CHECK(klv_back == klv_sent);
    CHECK(back_stats.cc_errors == 0);
}
