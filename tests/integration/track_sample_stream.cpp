// Writes the synthetic tracking scene (tests/unit/track/synthetic_scene.hpp) encoded as
// H.264 by lib/sim_video, for test_gimbal_track.py: the access units and, per frame, where
// the vehicle truly is.
//   track_sample_stream --scenario follow|bridge --frames N --out DIR
// DIR/units.bin: per access unit, little-endian: u32 length, i64 pts_90k, u8 key, the bytes.
// DIR/truth.jsonl: per frame {"i","pts_90k","t","box":[x0,y0,x1,y1] (image coordinates),
// "hidden" (the fraction the bridge covers)}.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include "encoded_scene.hpp"

namespace {

void put(std::ofstream& out, const void* p, std::size_t n) {
    out.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenario = "follow", dir = ".";
    int frames = 150;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--scenario") == 0)
            scenario = argv[i + 1];
        else if (std::strcmp(argv[i], "--frames") == 0)
            frames = std::atoi(argv[i + 1]);
        else if (std::strcmp(argv[i], "--out") == 0)
            dir = argv[i + 1];
    }
    track_test::SceneOptions o;
    if (scenario == "bridge") {
        o.route = {{40, 250}, {620, 250}};
        o.bridge = cv::Rect2d(200, 200, 154, 100);
    } else if (scenario == "follow") {
        o.route = {{60, 250}, {400, 250}, {600, 88}};
    } else {
        std::cerr << "track_sample_stream: --scenario follow or bridge\n";
        return 1;
    }
    const track_test::SyntheticScene scene(o);
    constexpr int fps = 15;
    const auto units = track_test::encode_scene(scene, frames, fps);
    std::ofstream bin(dir + "/units.bin", std::ios::binary);
    for (const auto& u : units) {
        const auto n = static_cast<std::uint32_t>(u.annex_b.size());
        const std::int64_t pts = u.pts_90k;  // little-endian on the machines this runs on
        const std::uint8_t key = u.key ? 1 : 0;
        put(bin, &n, 4);
        put(bin, &pts, 8);
        put(bin, &key, 1);
        put(bin, u.annex_b.data(), u.annex_b.size());
    }
    std::ofstream truth(dir + "/truth.jsonl");
    const double w = o.width, h = o.height;
    for (int i = 0; i < frames; ++i) {
        const double t = static_cast<double>(i) / fps;
        const auto b = scene.truth(t);
        char line[256];
        std::snprintf(line, sizeof(line),
                      "{\"i\":%d,\"pts_90k\":%d,\"t\":%.6f,\"box\":[%.6f,%.6f,%.6f,%.6f],"
                      "\"hidden\":%.4f}\n",
                      i, i * 90000 / fps, t, b.x / w * 2 - 1, b.y / h * 2 - 1,
                      (b.x + b.width) / w * 2 - 1, (b.y + b.height) / h * 2 - 1,
                      scene.occluded_fraction(t));
        truth << line;
    }
    std::cout << units.size() << " access units, " << frames << " frames\n";
    return bin && truth ? 0 : 1;
}
