#!/usr/bin/env bash
# Builds the benchmarks with the `release` preset and runs them. Extra arguments go to the
# benchmark program, e.g. scripts/bench.sh --benchmark_filter=Decode --benchmark_repetitions=5
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset release >/dev/null
cmake --build --preset release --target bench_orion -j "$jobs"
exec build/release/tests/bench/bench_orion "$@"
