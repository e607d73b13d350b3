#!/usr/bin/env bash
# Builds the benchmarks with the `release` preset and runs them: the Orion codec (Google
# Benchmark) and the video relay (1080p30 8 Mbit/s H.264 TS with KLV, UDP in -> 2 UDP outputs:
# CPU and latency, docs/video.md). Extra arguments go to the codec benchmark, e.g.
#   scripts/bench.sh --benchmark_filter=Decode --benchmark_repetitions=5
# scripts/bench.sh --smoke runs each for a few seconds (what CI can afford).
# VIDEO_SECONDS sets the relay run's length (default 10).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
smoke=0
if [ "${1:-}" = "--smoke" ]; then
  smoke=1
  shift
fi
cmake --preset release >/dev/null
cmake --build --preset release --target bench_orion bench_video_relay -j "$jobs"
video_dir=build/release/tests/bench/video
if [ $smoke = 1 ]; then
  build/release/tests/bench/bench_orion --benchmark_min_time=0.01 "$@"
  "$video_dir/bench_video_relay" --seconds 2 --dir "$video_dir"
else
  build/release/tests/bench/bench_orion "$@"
  "$video_dir/bench_video_relay" --seconds "${VIDEO_SECONDS:-10}" --dir "$video_dir"
fi
