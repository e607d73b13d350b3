// One ray-terrain intersection on a 1 arc-second model (contract section 15: p99 under
// 20 us). The model is made here: a 1 x 1 degree, 3601 x 3601 GeoTIFF of the simulator's
// terrain plus fractal relief down to 60 m wavelengths, written through GDAL into a temporary
// directory and read back with the EGM96 geoid. Rays start 300-3000 m above the ground and
// aim at ground points 1-20 km away; each is timed alone and p50/p99 reported as counters.
// Also what STATE pays per telemetry packet with terrain: the footprint's four corners and
// the ground under the line of sight (state::telemetry_json), computed once per packet.
//   bench_terrain                      the model built in a temporary directory (about 30 s)
//   bench_terrain --model-dir DIR      the model kept in DIR and used again by the next run
//   bench_terrain --smoke              the same model and rays, each benchmark run briefly
// Target (contract section 15): one intersection p99 under 20 us, printed as met or MISSED.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "geo/image.hpp"
#include "geo/wgs84.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/orion/orion_state.hpp"
#include "sim/terrain.hpp"
#include "terrain/elevation_model.hpp"
#include "terrain/geotiff_writer.hpp"

namespace {

using namespace gimbal;

// Smooth value noise: a hashed lattice value per integer point, smoothstep between them.
double lattice_value(std::int64_t i, std::int64_t j, std::uint64_t seed) {
    std::uint64_t h = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL ^
                      static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL ^ seed;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ULL;
    h ^= h >> 29;
    return static_cast<double>(h >> 11) / static_cast<double>(1ULL << 53) * 2 - 1;
}

double value_noise(double x, double y, std::uint64_t seed) {
    const double fx = std::floor(x), fy = std::floor(y);
    const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
    auto smooth = [](double t) { return t * t * (3 - 2 * t); };
    const double u = smooth(x - fx), v = smooth(y - fy);
    const double a = lattice_value(i, j, seed), b = lattice_value(i + 1, j, seed);
    const double c = lattice_value(i, j + 1, seed), d = lattice_value(i + 1, j + 1, seed);
    return (1 - v) * ((1 - u) * a + u * b) + v * ((1 - u) * c + u * d);
}

// The simulator's hills with ridges and gullies from 8 km down to 60 m.
double relief(double lat, double lon) {
    const double y = lat * 111000, x = lon * 78000;
    double h = sim::terrain_height(lat, lon);
    double wavelength = 8000, amplitude = 160;
    for (std::uint64_t octave = 0; octave < 8; ++octave) {
        h += amplitude * value_noise(x / wavelength, y / wavelength, octave + 1);
        wavelength /= 2;
        amplitude *= 0.55;
    }
    return h;
}

struct Ray {
    geo::Lla from;
    geo::Vec3 dir;
    double aimed_m;
};

struct Fixture {
    std::filesystem::path dir;
    bool keep = false;  // dir holds a model kept between runs
    std::unique_ptr<terrain::ElevationModel> model;
    std::vector<Ray> rays;
    double lat_min = 45.2, lon_min = -122.0, size = 1.0;
};

Fixture* fixture = nullptr;
double intersect_p99_us = -1;  // BM_Intersect's, for the verdict

// The model's file name says what it holds: a kept model is used again only when it is the
// same one (bump the version when relief() or the extent changes).
constexpr const char* model_name = "bench_terrain-relief-v1-45.2N122.0W-1deg.tif";

// `keep_dir`: where the model is kept between runs (empty: a temporary directory, removed).
void build(Fixture& f, const std::string& keep_dir) {
    if (keep_dir.empty()) {
        char tmpl[] = "/tmp/bench_terrain.XXXXXX";
        if (!mkdtemp(tmpl)) {
            std::perror("mkdtemp");
            std::exit(1);
        }
        f.dir = tmpl;
    } else {
        f.keep = true;
        f.dir = keep_dir;
        std::filesystem::create_directories(f.dir);
    }
    const auto file = (f.dir / model_name).string();
    const terrain::GridSpec spec{f.lat_min, f.lat_min + f.size, f.lon_min, f.lon_min + f.size,
                                 1.0 / 3600};
    if (f.keep && std::filesystem::exists(file)) {
        std::cerr << "model: " << file << " (kept from an earlier run)\n";
    } else {
        const auto t0 = std::chrono::steady_clock::now();
        // Written under a temporary name: an interrupted run leaves no half model behind.
        const auto partial = file + ".part";
        if (const auto e = terrain::write_geotiff(partial, spec, relief); !e.empty()) {
            std::cerr << e << "\n";
            std::exit(1);
        }
        std::filesystem::rename(partial, file);
        const auto t1 = std::chrono::steady_clock::now();
        std::cerr << "model: " << terrain::grid_cols(spec) << " x " << terrain::grid_rows(spec)
                  << " nodes at 1 arc-second, written in "
                  << std::chrono::duration<double>(t1 - t0).count() << " s\n";
    }
    terrain::TerrainOptions options;
    options.files = {file};
    options.cache_mb = 64;
    auto opened = terrain::ElevationModel::open(options);
    if (!opened) {
        std::cerr << opened.error().message << "\n";
        std::exit(1);
    }
    f.model = std::move(opened).value();

    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> unit(0, 1);
    const double margin = f.size * 0.15;
    const double max_m = 20000;
    while (f.rays.size() < 3000u) {
        const double lat = f.lat_min + margin + unit(rng) * (f.size - 2 * margin);
        const double lon = f.lon_min + margin + unit(rng) * (f.size - 2 * margin);
        const auto ground = f.model->height(lat, lon);
        if (!ground) continue;
        const geo::Lla from{lat, lon, *ground + 300 + unit(rng) * 2700};
        const double dist = 1000 + unit(rng) * (max_m - 1000);
        const double az = unit(rng) * 2 * geo::pi;
        const double tlat = lat + dist * std::cos(az) / 111000;
        const double tlon = lon + dist * std::sin(az) / (111000 * std::cos(lat * geo::deg2rad));
        const auto th = f.model->height(tlat, tlon);
        if (!th) continue;
        const geo::Vec3 d = geo::lla_to_ecef({tlat, tlon, *th}) - geo::lla_to_ecef(from);
        f.rays.push_back({from, d, geo::norm(d)});
    }
    // Warm the cache: the figure is the steady state of a flight over known ground.
    for (const Ray& r : f.rays) f.model->intersect(r.from, r.dir, {});
}

double percentile(std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    const auto i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
    return v[i];
}

void BM_Intersect(benchmark::State& state) {
    Fixture& f = *fixture;
    std::vector<double> us;
    std::size_t i = 0, hits = 0;
    double slant = 0;
    for (auto _ : state) {
        const Ray& r = f.rays[i++ % f.rays.size()];
        const auto t0 = std::chrono::steady_clock::now();
        const auto hit = f.model->intersect(r.from, r.dir, {});
        const auto t1 = std::chrono::steady_clock::now();
        benchmark::DoNotOptimize(hit);
        us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
        if (hit.status == geo::RayStatus::hit) {
            ++hits;
            slant += hit.range_m;
        }
    }
    state.counters["p50_us"] = percentile(us, 0.50);
    state.counters["p99_us"] = percentile(us, 0.99);
    intersect_p99_us = percentile(us, 0.99);
    state.counters["max_us"] = percentile(us, 1.0);
    state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(us.size());
    state.counters["mean_slant_km"] = hits ? slant / static_cast<double>(hits) / 1000 : 0;
}
BENCHMARK(BM_Intersect)->UseRealTime();

void BM_Height(benchmark::State& state) {
    Fixture& f = *fixture;
    std::size_t i = 0;
    for (auto _ : state) {
        const Ray& r = f.rays[i++ % f.rays.size()];
        benchmark::DoNotOptimize(f.model->height(r.from.lat_deg, r.from.lon_deg));
    }
}
BENCHMARK(BM_Height);

// A GeolocateTelemetry looking along a benchmark ray (level mount, a 40 x 22.5 degree view).
orion::GeolocateTelemetry telemetry_along(const Ray& r) {
    orion::GeolocateTelemetry t;
    t.lat = r.from.lat_deg * geo::deg2rad;
    t.lon = r.from.lon_deg * geo::deg2rad;
    t.alt = r.from.alt_m;
    t.quat = {1, 0, 0, 0};
    const geo::Lla aim = geo::ecef_to_lla(geo::lla_to_ecef(r.from) + r.dir);
    const auto pt = geo::pan_tilt_towards({}, r.from, aim);
    t.pan = pt ? pt->pan_deg * geo::deg2rad : 0;
    t.tilt = pt ? pt->tilt_deg * geo::deg2rad : -0.5;
    t.hfov = 40 * geo::deg2rad;
    t.vfov = 22.5 * geo::deg2rad;
    t.los_ecef = {r.dir.x, r.dir.y, r.dir.z};
    return t;
}

// STATE's telemetry key for one packet, with the ground keys on the terrain (arg 1) or on the
// flat world only (arg 0).
void BM_TelemetryGround(benchmark::State& state) {
    Fixture& f = *fixture;
    std::vector<orion::GeolocateTelemetry> packets;
    for (const Ray& r : f.rays) packets.push_back(telemetry_along(r));
    geo::Surface* terrain = state.range(0) ? f.model.get() : nullptr;
    std::vector<double> us;
    std::size_t i = 0, on_terrain = 0;
    for (auto _ : state) {
        const auto& t = packets[i++ % packets.size()];
        const auto t0 = std::chrono::steady_clock::now();
        auto j = state::telemetry_json(t, terrain);
        const auto t1 = std::chrono::steady_clock::now();
        if (j["footprint_surface"] == "terrain") ++on_terrain;
        benchmark::DoNotOptimize(j);
        us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
    state.counters["p50_us"] = percentile(us, 0.50);
    state.counters["p99_us"] = percentile(us, 0.99);
    state.counters["footprint_on_terrain"] =
        static_cast<double>(on_terrain) / static_cast<double>(us.size());
}
BENCHMARK(BM_TelemetryGround)->Arg(0)->Arg(1)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
    bool smoke = false;
    std::string keep_dir;
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i) {
        if (std::strcmp(argv[i], "--smoke") == 0)
            smoke = true;
        else if (std::strcmp(argv[i], "--model-dir") == 0 && i + 1 < argc)
            keep_dir = argv[++i];
        else
            args.push_back(argv[i]);
    }
    // Smoke: the same model and rays, each benchmark measured briefly.
    static char min_time[] = "--benchmark_min_time=0.05";
    if (smoke) args.push_back(min_time);
    int n = static_cast<int>(args.size());
    benchmark::Initialize(&n, args.data());
    Fixture f;
    fixture = &f;
    build(f, keep_dir);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    const auto stats = f.model->cache_stats();
    std::cerr << "cache: " << stats.loads << " blocks read, " << stats.resident << " resident of "
              << stats.capacity << "\n";
    if (intersect_p99_us >= 0)
        std::cout << "intersection p99 " << intersect_p99_us
                  << " us (target < 20 us: " << (intersect_p99_us < 20 ? "met" : "MISSED") << ")\n";
    f.model.reset();
    if (!f.keep) std::filesystem::remove_all(f.dir);
    return 0;
}
