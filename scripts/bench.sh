#!/usr/bin/env bash
# Builds the benchmarks with the `release` preset and runs them: the Orion codec (bench_orion),
# MISB ST 0601 KLV generation and decoding (bench_klv), one ray-terrain intersection on a
# 1 arc-second model (bench_terrain, docs/terrain.md "Cost"), the video relay: a 1080p30
# 8 Mbit/s H.264 TS with KLV from a UDP input to two UDP outputs (bench_video_relay, CPU and
# latency, docs/video.md "Relay budget"; VIDEO_SECONDS sets its length, default 10), then the
# simulated camera's render + encode at 640x360 15 fps (bench_sim_video, docs/simulator.md
# "Cost"). Extra arguments go to each Google Benchmark program, bench_terrain and
# bench_sim_video, e.g.
#   scripts/bench.sh --benchmark_filter=Decode --benchmark_repetitions=5
#   scripts/bench.sh --smoke     a few seconds: every benchmark briefly (the small terrain
#                                model), a check for CI that they build and run; its timings
#                                mean nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
smoke=()
args=()
for a in "$@"; do
  if [ "$a" = "--smoke" ]; then smoke=(--smoke); else args+=("$a"); fi
done
google_smoke=()
[ ${#smoke[@]} -gt 0 ] && google_smoke=(--benchmark_min_time=0.01)
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset release >/dev/null
cmake --build --preset release --target bench_orion bench_klv bench_terrain bench_video_relay \
  bench_sim_video -j "$jobs"
build/release/tests/bench/bench_orion ${google_smoke[@]+"${google_smoke[@]}"} ${args[@]+"${args[@]}"}
build/release/tests/bench/bench_klv ${google_smoke[@]+"${google_smoke[@]}"} ${args[@]+"${args[@]}"}
build/release/tests/bench/terrain/bench_terrain ${smoke[@]+"${smoke[@]}"} ${args[@]+"${args[@]}"}
video_dir=build/release/tests/bench/video
if [ ${#smoke[@]} -gt 0 ]; then
  "$video_dir/bench_video_relay" --smoke --dir "$video_dir"
else
  "$video_dir/bench_video_relay" --seconds "${VIDEO_SECONDS:-10}" --dir "$video_dir"
fi
exec build/release/tests/bench/sim_video/bench_sim_video ${smoke[@]+"${smoke[@]}"} ${args[@]+"${args[@]}"}
