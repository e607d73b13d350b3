#!/usr/bin/env bash
# Builds the benchmarks with the `release` preset and runs them: the Orion codec (bench_orion)
# and MISB ST 0601 KLV generation and decoding (bench_klv). Extra arguments go to each
# benchmark program, e.g. scripts/bench.sh --benchmark_filter=Decode --benchmark_repetitions=5
# --smoke (first argument) runs every benchmark for a few milliseconds only: a check that they
# build and run, for CI; its timings mean nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
smoke=()
if [[ "${1:-}" == --smoke ]]; then
    smoke=(--benchmark_min_time=0.01)
    shift
fi
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset release >/dev/null
cmake --build --preset release --target bench_orion bench_klv -j "$jobs"
build/release/tests/bench/bench_orion "${smoke[@]}" "$@"
build/release/tests/bench/bench_klv "${smoke[@]}" "$@"
