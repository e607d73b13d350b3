// Orion codec speed: framer throughput over a stream of mixed valid packets, and the decode
// and encode of a full (89-byte) GeolocateTelemetry. Targets: >= 1 GB/s, < 100 ns.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/packets.hpp"

namespace {

namespace orion = gimbal::orion;
using Bytes = std::vector<std::uint8_t>;

// One full-length wire frame of every packet type (random content decoded and re-encoded).
std::vector<Bytes> sample_frames() {
    std::mt19937 rng(1);
    std::vector<Bytes> frames;
    orion::for_each_packet([&]<class P>() {
        Bytes data(P::max_length);
        for (auto& b : data) b = static_cast<std::uint8_t>(rng());
        P packet{};
        if (auto d = orion::decode<P>(data)) packet = d.value;
        frames.push_back(orion::to_wire(packet));
    });
    return frames;
}

// 16 MiB of those frames in random order: what a busy link delivers.
const Bytes& mixed_stream() {
    static const Bytes stream = [] {
        const std::vector<Bytes> frames = sample_frames();
        std::mt19937 rng(2);
        Bytes out;
        out.reserve((16u << 20) + orion::max_frame_size);
        while (out.size() < (16u << 20)) {
            const Bytes& f = frames[rng() % frames.size()];
            out.insert(out.end(), f.begin(), f.end());
        }
        return out;
    }();
    return stream;
}

// Arg: bytes per push() (a read() buffer); 0 pushes the whole stream at once.
void BM_FramerThroughput(benchmark::State& state) {
    const Bytes& stream = mixed_stream();
    const auto chunk = static_cast<std::size_t>(state.range(0));
    std::uint64_t packets = 0;
    for (auto _ : state) {
        orion::Framer framer;
        const std::span<const std::uint8_t> all(stream);
        const std::size_t step = chunk ? chunk : all.size();
        for (std::size_t at = 0; at < all.size(); at += step)
            framer.push(all.subspan(at, std::min(step, all.size() - at)),
                        [&](const orion::Frame& f) { benchmark::DoNotOptimize(f.payload.size); });
        packets += framer.stats().packets;
        if (framer.stats().dropped_bytes != 0) state.SkipWithError("stream was not all valid");
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(stream.size()));
    state.counters["packets/s"] =
        benchmark::Counter(static_cast<double>(packets), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FramerThroughput)->Arg(0)->Arg(4096)->Arg(256)->Unit(benchmark::kMillisecond);

// A GeolocateTelemetry with every field, INS quaternion included: 89 data bytes.
orion::GeolocateTelemetry full_telemetry() {
    orion::GeolocateTelemetry t;
    t.system_time_ms = 123456789;
    t.gps_itow_ms = 345600000;
    t.gps_week = 2330;
    t.geoid_undulation = -19.5;
    t.lat = 45.7 * orion::pi / 180;
    t.lon = -121.5 * orion::pi / 180;
    t.alt = 1500.25;
    t.vel_ned = {12.5, -3.25, 0.5};
    t.quat = {0.9515, 0.0381, 0.1893, 0.2393};
    t.pan = 0.5;
    t.tilt = -0.75;
    t.hfov = 0.3;
    t.vfov = 0.17;
    t.los_ecef = {-250, 400, -900};
    t.pixel_width = 1920;
    t.pixel_height = 1080;
    t.mode = orion::Mode::geopoint;
    t.path_progress = 0.5;
    t.stare_time_s = 1.2;
    t.image_shifts = {0.001, -0.002};
    t.image_shift_delta_time_s = 0.1;
    t.image_shift_confidence = 0.9;
    t.output_shifts = {0.01, -0.01};
    t.range_source = orion::RangeSource::laser;
    t.pan_alignment = 0.01;
    t.tilt_alignment = -0.01;
    t.ins_rotation_option = orion::InsRotation::platform;
    t.ins_quat = {1, 0, 0, 0};
    return t;
}

void BM_DecodeTelemetry(benchmark::State& state) {
    const orion::Payload wire = orion::encode(full_telemetry());
    if (wire.size != orion::GeolocateTelemetry::max_length) state.SkipWithError("not 89 bytes");
    for (auto _ : state) {
        auto d = orion::decode<orion::GeolocateTelemetry>(wire.view());
        benchmark::DoNotOptimize(d);
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(wire.size));
}
BENCHMARK(BM_DecodeTelemetry);

void BM_EncodeTelemetry(benchmark::State& state) {
    const orion::GeolocateTelemetry t = full_telemetry();
    orion::Payload out;
    for (auto _ : state) {
        benchmark::DoNotOptimize(orion::encode(t, out));
        benchmark::DoNotOptimize(out);
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(out.size));
}
BENCHMARK(BM_EncodeTelemetry);

}  // namespace

BENCHMARK_MAIN();
