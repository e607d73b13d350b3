// MISB ST 0601 KLV cost (lib/klv): building and encoding the set gimbald generates per video
// frame (contract section 17: 26 items - time stamp, mission, platform attitude, sensor
// position, field of view, sensor angles, slant range, frame centre, four corner offsets,
// flags, version, checksum), decoding it to JSON, and finding sets in a PES payload.
// Budget: KLV generation at 30 Hz under 0.2 % of a core, i.e. under 67 us a set.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>

#include "klv/local_set.hpp"
#include "klv/mapping.hpp"

namespace {

namespace klv = gimbal::klv;

// What a generator fills from STATE, in the order of contract section 17.
klv::LocalSet typical_set(std::uint64_t time_us, double wobble) {
    klv::LocalSet set;
    set.items.reserve(26);
    set.add(klv::tag_of("precision_time_stamp"), time_us);
    set.add(klv::tag_of("mission_id"), std::string("GIMBALD-TEST-01"));
    set.add(klv::tag_of("platform_heading_angle"), 87.25 + wobble);
    set.add(klv::tag_of("platform_pitch_angle"), 2.5);
    set.add(klv::tag_of("platform_roll_angle"), -1.25);
    set.add(klv::tag_of("sensor_latitude"), 47.3977419 + wobble * 1e-6);
    set.add(klv::tag_of("sensor_longitude"), 8.5455938);
    set.add(klv::tag_of("sensor_true_altitude"), 612.4);
    set.add(klv::tag_of("sensor_horizontal_field_of_view"), 12.3);
    set.add(klv::tag_of("sensor_vertical_field_of_view"), 6.9);
    set.add(klv::tag_of("sensor_relative_azimuth_angle"), 311.7);
    set.add(klv::tag_of("sensor_relative_elevation_angle"), -35.2);
    set.add(klv::tag_of("sensor_relative_roll_angle"), 0.0);
    set.add(klv::tag_of("slant_range"), 842.6);
    set.add(klv::tag_of("frame_center_latitude"), 47.4012);
    set.add(klv::tag_of("frame_center_longitude"), 8.5391);
    set.add(klv::tag_of("frame_center_elevation"), 421.7);
    for (std::uint32_t tag = 26; tag <= 33; ++tag)
        set.add(tag, (tag % 2 == 0 ? 0.0021 : -0.0034) * (tag - 25));
    set.add(klv::tag_of("generic_flag_data"), std::uint64_t{0x11});
    set.add(klv::tag_of("uas_datalink_ls_version_number"), std::uint64_t{klv::st0601_version});
    return set;
}

// Building the set from values and encoding it: the whole per-frame cost of generation.
void BM_GenerateTypicalSet(benchmark::State& state) {
    std::uint64_t t = 1'800'000'000'000'000;
    std::size_t bytes = 0;
    for (auto _ : state) {
        const klv::Encoded e = klv::encode(typical_set(t, static_cast<double>(t % 7)));
        bytes = e.value().size();
        benchmark::DoNotOptimize(e.value().data());
        t += 33'333;
    }
    state.counters["set_bytes"] = static_cast<double>(bytes);
    state.counters["items"] = 26;
}
BENCHMARK(BM_GenerateTypicalSet);

void BM_EncodeTypicalSet(benchmark::State& state) {
    const klv::LocalSet set = typical_set(1'800'000'000'000'000, 0.0);
    for (auto _ : state) {
        const klv::Encoded e = klv::encode(set);
        benchmark::DoNotOptimize(e.value().data());
    }
}
BENCHMARK(BM_EncodeTypicalSet);

// Decoding with JSON as STATE's "klv" shows it (fewest digits), and with exact doubles.
void BM_DecodeTypicalSet(benchmark::State& state) {
    const klv::Bytes bytes = klv::encode(typical_set(1'800'000'000'000'000, 0.0)).value();
    const auto digits = state.range(0) == 0 ? klv::Digits::shortest : klv::Digits::exact;
    for (auto _ : state) {
        const klv::DecodeResult r = klv::decode(bytes, digits);
        benchmark::DoNotOptimize(r.json.size());
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(bytes.size()));
}
BENCHMARK(BM_DecodeTypicalSet)->Arg(0)->Arg(1)->ArgNames({"exact"});

// A PES payload of four sets with junk before: locating them.
void BM_FindSets(benchmark::State& state) {
    klv::Bytes payload{0x00, 0x47, 0x06, 0x0E};
    for (unsigned i = 0; i < 4; ++i) {
        const klv::Bytes one =
            klv::encode(typical_set(1'800'000'000'000'000 + 33'333u * i, i)).value();
        payload.insert(payload.end(), one.begin(), one.end());
    }
    for (auto _ : state) {
        const klv::FoundSets f = klv::find_sets(payload);
        benchmark::DoNotOptimize(f.sets.data());
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(payload.size()));
}
BENCHMARK(BM_FindSets);

}  // namespace

BENCHMARK_MAIN();
