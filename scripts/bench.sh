#!/usr/bin/env bash
# Builds the benchmarks with the `release` preset and runs them: the Orion codec (bench_orion),
# MISB ST 0601 KLV generation and decoding (bench_klv), one ray-terrain intersection on a
# 1 arc-second model (bench_terrain, docs/terrain.md "Cost"), then the simulated camera's
# render + encode at 640x360 15 fps (bench_sim_video, docs/simulator.md "Cost"). Extra
# arguments go to each benchmark program, e.g.
# scripts/bench.sh --benchmark_filter=Decode --benchmark_repetitions=5
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
cmake --build --preset release --target bench_orion bench_klv bench_terrain bench_sim_video -j "$jobs"
build/release/tests/bench/bench_orion ${google_smoke[@]+"${google_smoke[@]}"} ${args[@]+"${args[@]}"}
build/release/tests/bench/bench_klv ${google_smoke[@]+"${google_smoke[@]}"} ${args[@]+"${args[@]}"}
build/release/tests/bench/terrain/bench_terrain ${smoke[@]+"${smoke[@]}"} ${args[@]+"${args[@]}"}
exec build/release/tests/bench/sim_video/bench_sim_video ${smoke[@]+"${smoke[@]}"} ${args[@]+"${args[@]}"}
