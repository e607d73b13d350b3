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

MOVING OBJECTS
       The picture shows the simulator's roads and, with --objects (default
       all), vehicles driving them at 5-25 m/s and a boat on the river, each
       where it is at the model's time (the same places on every run): car
       (white, eastbound on the east-west road at 15 m/s, 1.5 km west of the
       circle's centre at the start), convoy1..convoy5 (westbound at 15 m/s,
       passing under the highway's overpass 24, 36, 48, 60 and 72 s after the
       start, out of sight for about 2 s), truck and highway_car (the
       highway), hill_car and tractor (round the east hill, which hides them
       from parts of the circle) and boat (the river, 6 m/s). --objects none
       shows the roads only. --objects-log FILE writes their truth, one JSON
       line per object per frame: frame, unix_us, pts_90k, model time t, name,
       kind, lat, lon, alt, heading, speed, north, east, slant_range_m, image
       x, y and box (section 16 coordinates, from the frame's camera pose),
       in_picture, visible (the fraction of the body in sight) and hidden
       (null, "deck" or "terrain"). See docs/simulator.md "Moving objects".
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
    app.add_option("--objects", o.objects,
                   "Moving objects in the picture: all, none, or names (MOVING OBJECTS)")
        ->type_name("LIST")
        ->capture_default_str()
        ->group(group);
    app.add_option("--objects-log", o.objects_log,
                   "Write the objects' truth to FILE, a JSON line per object per frame")
        ->type_name("FILE")
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
    std::string why;
    const auto objects = gimbal::sim::ObjectSet::parse(o.objects, why);
    if (!objects) {
        error = "--objects: " + why;
        return std::nullopt;
    }
    s.stream.video.objects = *objects;
    s.objects_log = o.objects_log;
    if (const std::string problem = gimbal::sim_video::check(s.stream.video.h264);
        !problem.empty()) {
        error = "--video: " + problem;
        return std::nullopt;
    }
    return s;
}

}  // namespace gimbal_sim
