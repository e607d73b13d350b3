#!/usr/bin/env bash
# Builds the benchmarks with the `release` preset and runs them: the Orion codecs, one
# ray-terrain intersection on a 1 arc-second model (docs/terrain.md "Cost"), then the simulated
# camera's render + encode at 640x360 15 fps (docs/simulator.md "Cost"). Extra arguments go to
# every program, e.g. scripts/bench.sh --benchmark_repetitions=5.
#   scripts/bench.sh --smoke     a few seconds: every benchmark briefly, the small terrain model
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
smoke=()
args=()
for a in "$@"; do
  if [ "$a" = "--smoke" ]; then smoke=(--smoke); else args+=("$a"); fi
done
cmake --preset release >/dev/null
cmake --build --preset release --target bench_orion bench_terrain bench_sim_video -j "$jobs"
if [ ${#smoke[@]} -gt 0 ]; then
  build/release/tests/bench/bench_orion --benchmark_min_time=0.01 ${args[@]+"${args[@]}"}
else
  build/release/tests/bench/bench_orion ${args[@]+"${args[@]}"}
fi
build/release/tests/bench/terrain/bench_terrain ${smoke[@]+"${smoke[@]}"} ${args[@]+"${args[@]}"}
exec build/release/tests/bench/sim_video/bench_sim_video ${smoke[@]+"${smoke[@]}"} ${args[@]+"${args[@]}"}
