#include "video_options.hpp"

#include <cstdio>

#include "sim_video/h264_encoder.hpp"
#include "video/url.hpp"

namespace gimbal_sim {

std::string video_manual() {
    std::string with_camera;
    for (const auto* p : gimbal::protocols::entries())
        if (p->simulator.camera != nullptr)
            with_camera += (with_camera.empty() ? "" : ", ") + std::string(p->name);
    return R"(
VIDEO
       --video udp://HOST:PORT[?ttl=N] sends the simulated camera's picture
       (protocols whose model has a camera: )" +
           with_camera + R"()
       as H.264 in MPEG-TS with MISB ST 0601 KLV, as a real Orion does with
       STREAM_TYPE_H264: the simulator's terrain rendered from the camera's
       pose, the frame's time drawn in the top-left corner, one KLV set per
       frame (sensor, platform, frame centre and corners on the terrain).
       Rendering and encoding run on their own thread. On standard output:
       "video: udp://HOST:PORT"; at the end, on standard error, the frames sent
       and the CPU they took. Watch it with ffplay udp://HOST:PORT (see
       docs/video.md), or give gimbald "video": {"input": "udp://0.0.0.0:PORT"}.
)";
}

void add_video_options(CLI::App& app, VideoToolOptions& o) {
    const std::string group = "Video (docs/video.md)";
    app.add_option("--video", o.url,
                   "Send the camera's video as MPEG-TS with KLV to udp://HOST:PORT[?ttl=N]")
        ->type_name("URL")
        ->group(group);
    app.add_option("--video-size", o.size, "Picture size WIDTHxHEIGHT (even, 16..4096)")
        ->type_name("WxH")
        ->capture_default_str()
        ->group(group);
    app.add_option("--video-fps", o.fps, "Frames per second")
        ->check(CLI::Range(1, 60))
        ->capture_default_str()
        ->group(group);
    app.add_option("--video-bitrate", o.bitrate_bps, "H.264 bit rate, bits per second")
        ->check(CLI::Range(50000, 50000000))
        ->capture_default_str()
        ->group(group);
    app.add_flag(
           "--no-video-klv", [&o](std::int64_t) { o.klv = false; },
           "No KLV in the video (an Orion with its KLV output off)")
        ->group(group);
}

std::optional<gimbald::video::SimVideoSenderOptions> video_sender_options(
    const VideoToolOptions& o, const gimbal::protocols::Entry& entry, std::string& error) {
    if (entry.simulator.camera == nullptr) {
        error = "--video: the " + std::string(entry.name) + " simulator has no camera";
        return std::nullopt;
    }
    const auto parsed = gimbal::video::parse_video_url(o.url);
    if (!parsed || parsed->scheme != gimbal::video::UrlScheme::udp || parsed->host.empty()) {
        error = "--video: expected udp://HOST:PORT[?ttl=N]" +
                (parsed ? std::string() : " (" + parsed.error().message + ")");
        return std::nullopt;
    }
    int width = 0, height = 0;
    char end = 0;
    if (std::sscanf(o.size.c_str(), "%dx%d%c", &width, &height, &end) != 2 || width < 16 ||
        height < 16 || width > 4096 || height > 4096 || width % 2 != 0 || height % 2 != 0) {
        error = "--video-size: expected WIDTHxHEIGHT, even, 16..4096 (e.g. 640x360)";
        return std::nullopt;
    }
    gimbald::video::SimVideoSenderOptions s;
    s.host = parsed->host;
    s.port = parsed->port;
    s.ttl = parsed->ttl;
    s.stream.video.scene.width = width;
    s.stream.video.scene.height = height;
    s.stream.video.h264.fps = o.fps;
    s.stream.video.h264.bitrate_bps = o.bitrate_bps;
    s.stream.video.h264.width = width;  // SimVideoSource sets them from the scene too
    s.stream.video.h264.height = height;
    s.stream.klv = o.klv;
    if (const std::string problem = gimbal::sim_video::check(s.stream.video.h264);
        !problem.empty()) {
        error = "--video: " + problem;
        return std::nullopt;
    }
    return s;
}

}  // namespace gimbal_sim
