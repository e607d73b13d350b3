// The encoded video read by tools nobody here wrote: ffprobe finds H.264 constrained baseline
// 640x360 with the frames and key frames we made; ffmpeg decodes it, and in the decoded
// pictures the time code still reads and the landmarks keep their colours where
// geo::project puts them.
#include <catch2/catch.hpp>
#include <map>
#include <sstream>

#include "../sim/scene_test_support.hpp"
#include "sim/frame_code.hpp"
#include "sim/scene_renderer.hpp"
#include "sim_video/h264_encoder.hpp"
#include "video_test_support.hpp"

using namespace gimbal;
using namespace gimbal::sim_video;
using namespace video_test;

namespace {

constexpr int frames = 30;  // two seconds at 15 fps
constexpr std::uint64_t t0_ms = 1735689600000ull;

std::uint64_t frame_time(int i) {
    return t0_ms + static_cast<std::uint64_t>(i) * 1000 / 15;
}

// A camera 2.5 km south-west of its landmark at 1500 m, drifting along, switching landmark
// every six frames (a hard cut for the encoder).
geo::CameraPose camera_for(int i) {
    const std::size_t target = static_cast<std::size_t>(i / 6) % sim::landmarks().size();
    const geo::Lla ground = scene_test::ground_near(target, -1800 + 2.0 * i, -1700);
    return scene_test::aimed({ground.lat_deg, ground.lon_deg, 1500},
                             scene_test::landmark_lla(target), 20);
}

std::map<std::string, std::string> key_values(const std::string& text) {
    std::map<std::string, std::string> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        if (const auto eq = line.find('='); eq != std::string::npos)
            out[line.substr(0, eq)] = line.substr(eq + 1);
    return out;
}

struct Encoded {
    std::vector<sim::I420Frame> pictures;
    std::vector<AccessUnit> units;
};

Encoded encode_sequence() {
    Encoded e;
    auto opened = H264Encoder::open({});
    REQUIRE(opened);
    sim::SceneRenderer renderer;
    for (int i = 0; i < frames; ++i) {
        sim::I420Frame picture;
        renderer.render(camera_for(i), picture);
        REQUIRE(sim::draw_frame_code(picture, frame_time(i)));
        REQUIRE((*opened)->encode(picture, i * 6000, e.units));
        e.pictures.push_back(std::move(picture));
    }
    REQUIRE((*opened)->flush(e.units));
    REQUIRE(e.units.size() == frames);
    return e;
}

}  // namespace

TEST_CASE("encoded video: ffprobe reads h264 640x360, the frames and the key frames",
          "[sim_video][ffmpeg]") {
    REQUIRE(have_tool("ffprobe"));  // Debian's ffmpeg package (scripts/install-deps.sh)
    TempDir dir;
    REQUIRE(dir.ok());
    const Encoded e = encode_sequence();
    const std::string path = dir.file("sim.h264");
    write_stream(path, e.units);
    int status = 0;
    const auto stream = key_values(
        run("ffprobe -v error -f h264 -count_frames -select_streams v:0 -show_entries "
            "stream=codec_name,profile,level,width,height,pix_fmt,color_range,color_space,"
            "nb_read_frames -of default=noprint_wrappers=1 " +
                path,
            status));
    REQUIRE(status == 0);
    CHECK(stream.at("codec_name") == "h264");
    CHECK(stream.at("profile") == "Constrained Baseline");
    CHECK(stream.at("level") == "30");
    CHECK(stream.at("width") == "640");
    CHECK(stream.at("height") == "360");
    CHECK(stream.at("pix_fmt") == "yuv420p");
    CHECK(stream.at("color_range") == "tv");
    CHECK(stream.at("color_space") == "smpte170m");
    CHECK(stream.at("nb_read_frames") == std::to_string(frames));

    const std::string flags =
        run("ffprobe -v error -f h264 -select_streams v:0 -show_entries frame=key_frame,pict_type "
            "-of csv=p=0 " +
                path,
            status);
    REQUIRE(status == 0);
    std::istringstream lines(flags);
    std::string line;
    std::vector<int> keys;
    int n = 0;
    while (std::getline(lines, line)) {
        if (line.empty()) continue;
        // key_frame,pict_type[,side data...]
        const std::string key = line.substr(0, line.find(','));
        const std::string type = line.substr(key.size() + 1, 1);
        if (key == "1") {
            keys.push_back(n);
            CHECK(type == "I");
        } else {
            CHECK(type == "P");  // no B-frames
        }
        ++n;
    }
    CHECK(n == frames);
    CHECK(keys == std::vector<int>{0, 15});
}

TEST_CASE("encoded video: decoded by ffmpeg, the time code and landmarks survive",
          "[sim_video][ffmpeg]") {
    REQUIRE(have_tool("ffmpeg"));
    TempDir dir;
    REQUIRE(dir.ok());
    const Encoded e = encode_sequence();
    write_stream(dir.file("sim.h264"), e.units);
    int status = 0;
    run("ffmpeg -v error -y -f h264 -i " + dir.file("sim.h264") + " -f rawvideo -pix_fmt yuv420p " +
            dir.file("sim.yuv"),
        status);
    REQUIRE(status == 0);
    const auto raw = read_file(dir.file("sim.yuv"));
    const std::size_t frame_bytes = 640 * 360 * 3 / 2;
    REQUIRE(raw.size() == frame_bytes * frames);
    int landmarks_checked = 0;
    for (int i = 0; i < frames; ++i) {
        INFO("frame " << i);
        const std::uint8_t* base = raw.data() + frame_bytes * static_cast<std::size_t>(i);
        const scene_test::PlaneView decoded{
            base, base + 640 * 360, base + 640 * 360 * 5 / 4, 640, 360, 640, 320};
        // The time code reads back exactly.
        const auto code = sim::decode_frame_code({base, 640 * 360}, 640, 360, 640);
        REQUIRE(code);
        CHECK(*code == frame_time(i));
        // Every landmark recognisable in the rendered picture at its projected pixel is still
        // recognisable there after H.264.
        const geo::CameraPose camera = camera_for(i);
        for (std::size_t k = 0; k < sim::landmarks().size(); ++k) {
            const auto p = scene_test::projected(camera, scene_test::landmark_lla(k));
            if (!p) continue;
            const int px = static_cast<int>(p->px), py = static_cast<int>(p->py);
            if (scene_test::landmark_colour_at(
                    scene_test::view(e.pictures[static_cast<std::size_t>(i)]).at(px, py), 12) != k)
                continue;
            const scene_test::Pixel got = decoded.at(px, py);
            INFO(sim::landmarks()[k].name << " at " << px << "," << py << ": " << got.y << " "
                                          << got.u << " " << got.v);
            CHECK(scene_test::landmark_colour_at(got, 40) == k);
            ++landmarks_checked;
        }
    }
    CHECK(landmarks_checked >= frames);  // at least the aimed one in every frame
}
