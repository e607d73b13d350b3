// The simulated Orion's video: render the scene (sim::SceneRenderer), draw the time code,
// encode it (sim_video::H264Encoder) at 640x360, 15 fps, 1.2 Mbit/s - what gimbal-sim and
// gimbald --sim spend per second of video (issue 20 asks for it). Each iteration is one frame
// of the model's time; render and encode are timed apart, in thread CPU time (the encoder
// runs one thread) and wall time, and reported as counters (the roads and every moving object
// drawn, as by default):
//   cpu_pct_15fps   CPU per second of video, percent of one core (render + encode)
//   render_p50_ms, render_p99_ms, encode_p50_ms, encode_p99_ms, frame_p50_ms, frame_p99_ms
//   kbit_s          the encoded bitrate
// Scenarios: the gimbal as it starts (ahead and 30 degrees down) while the aircraft circles and
// the gimbal pans slowly; staring at the summit (geopoint); looking out at the horizon (long
// grazing rays and hill edges: the renderer's worst case).
//   bench_sim_video            two seconds per scenario
//   bench_sim_video --smoke    a fraction of a second each
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <ctime>
#include <iostream>
#include <vector>

#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/orion/sim/orion_sim.hpp"
#include "protocols/orion/sim/sim_camera.hpp"
#include "sim/frame_code.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/terrain.hpp"
#include "sim_video/h264_encoder.hpp"

namespace {

using namespace gimbal;

constexpr int fps = 15;

double thread_cpu_s() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

enum Scenario { circling = 0, staring = 1, horizon = 2 };

template <class P>
void command(sim::Device& device, const P& packet, double t) {
    device.receive(orion::to_wire(packet), t);
}

void BM_RenderEncode(benchmark::State& state) {
    const auto scenario = static_cast<Scenario>(state.range(0));
    auto device = sim::make_orion_sim();
    std::vector<std::uint8_t> sink;
    device->advance(0, sink);
    if (scenario == circling) {
        orion::Cmd cmd;  // pan slowly while the aircraft circles
        cmd.cmd.mode = orion::Mode::rate;
        cmd.cmd.target = {0.1, 0};
        command(*device, cmd, 0);
    } else if (scenario == staring) {
        const auto& summit = sim::landmarks().front();
        orion::GeopointCmd g;
        g.target_lat = summit.lat_deg * geo::deg2rad;
        g.target_lon = summit.lon_deg * geo::deg2rad;
        g.target_alt = summit.alt_m;
        command(*device, g, 0);
    } else {
        orion::Cmd cmd;  // stabilized: north, 4 degrees down
        cmd.cmd.mode = orion::Mode::position;
        cmd.cmd.stabilized = true;
        cmd.cmd.target = {0, -4 * geo::deg2rad};
        command(*device, cmd, 0);
    }
    device->advance(3, sink);  // let the axes get there

    auto opened = sim_video::H264Encoder::open({});
    if (!opened) {
        state.SkipWithError(opened.error().message.c_str());
        return;
    }
    sim::SceneRenderer renderer;
    sim::I420Frame picture;
    std::vector<sim_video::AccessUnit> units;
    std::vector<double> render_ms, encode_ms, frame_ms;
    double cpu_s = 0, rays = 0;
    std::size_t bytes = 0;
    const sim::ObjectSet objects = sim::ObjectSet::all();
    int frame = 0;
    for (auto _ : state) {
        const double t = 3 + static_cast<double>(frame) / fps;
        sink.clear();
        device->advance(t, sink);
        const auto view = sim::orion_sim_camera(*device);
        const auto w0 = std::chrono::steady_clock::now();
        const double c0 = thread_cpu_s();
        renderer.set_monochrome(view->infrared);
        // With the moving objects, as gimbal-sim and gimbald --sim draw them by default.
        renderer.render(sim::camera_pose(*view), picture, objects.at(t));
        sim::draw_frame_code(picture, 1735689600000ull + static_cast<std::uint64_t>(t * 1000));
        const double c1 = thread_cpu_s();
        units.clear();
        if (!(*opened)->encode(picture, static_cast<std::int64_t>(frame) * 90000 / fps, units)) {
            state.SkipWithError((*opened)->error().c_str());
            return;
        }
        const double c2 = thread_cpu_s();
        const auto w2 = std::chrono::steady_clock::now();
        for (const auto& u : units) bytes += u.annex_b.size();
        render_ms.push_back((c1 - c0) * 1e3);
        encode_ms.push_back((c2 - c1) * 1e3);
        frame_ms.push_back(std::chrono::duration<double, std::milli>(w2 - w0).count());
        cpu_s += c2 - c0;
        rays += renderer.stats().rays;
        ++frame;
    }
    const double n = std::max(1, frame);
    state.counters["cpu_pct_15fps"] = cpu_s / n * fps * 100;
    state.counters["render_p50_ms"] = percentile(render_ms, 0.5);
    state.counters["render_p99_ms"] = percentile(render_ms, 0.99);
    state.counters["encode_p50_ms"] = percentile(encode_ms, 0.5);
    state.counters["encode_p99_ms"] = percentile(encode_ms, 0.99);
    state.counters["frame_p50_ms"] = percentile(frame_ms, 0.5);
    state.counters["frame_p99_ms"] = percentile(frame_ms, 0.99);
    state.counters["kbit_s"] = static_cast<double>(bytes) * 8 / 1000 / (n / fps);
    state.counters["rays"] = rays / n;
}
BENCHMARK(BM_RenderEncode)
    ->ArgName("scenario")
    ->Arg(circling)
    ->Arg(staring)
    ->Arg(horizon)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
    bool smoke = false;
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        if (std::strcmp(argv[i], "--smoke") == 0)
            smoke = true;
        else
            args.push_back(argv[i]);
    }
    static char min_time[] = "--benchmark_min_time=2";
    static char smoke_time[] = "--benchmark_min_time=0.2";
    args.insert(args.begin() + 1, smoke ? smoke_time : min_time);
    int n = static_cast<int>(args.size());
    benchmark::Initialize(&n, args.data());
    std::cerr << "scenario 0: circling, the gimbal panning slowly; 1: staring at the summit; "
                 "2: looking at the horizon\n";
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
