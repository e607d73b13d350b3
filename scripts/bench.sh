#!/usr/bin/env bash
# Builds the benchmarks with the `release` preset and runs them. Extra arguments go to the
# benchmark program, e.g. scripts/bench.sh --benchmark_filter=Decode --benchmark_repetitions=5
#
#   --smoke     a few seconds: every codec benchmark once, briefly, and the recorder
#               benchmark for one second; fails when one does not run or the recorder drops
#               a packet (timings are not checked). ctest runs it as "bench: bench.sh --smoke".
#   --no-build  use the programs already built in BUILD_DIR
#
# Environment: BUILD_DIR, an already configured build directory instead of build/release.
set -euo pipefail
cd "$(dirname "$0")/.."
smoke=false
build_it=true
args=()
for arg in "$@"; do
    case "$arg" in
        --smoke) smoke=true ;;
        --no-build) build_it=false ;;
        *) args+=("$arg") ;;
    esac
done
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
if [[ -n "${BUILD_DIR:-}" ]]; then
    build=$BUILD_DIR
else
    cmake --preset release >/dev/null
    build=build/release
fi
targets=(bench_orion)
$smoke && targets+=(bench_record)
$build_it && cmake --build "$build" --target "${targets[@]}" -j "$jobs"
orion=$build/tests/bench/bench_orion

if ! $smoke; then
    exec "$orion" "${args[@]}"
fi

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "bench.sh --smoke: FAILED: $*" >&2; exit 1; }

# Every registered benchmark must run and report; none may print an error.
expected=$("$orion" --benchmark_list_tests | wc -l)
"$orion" --benchmark_min_time=0.01 --benchmark_format=json >"$out/orion.json" 2>"$out/orion.err" ||
    fail "bench_orion exited $?: $(cat "$out/orion.err")"
python3 - "$out/orion.json" "$expected" <<'PY' || fail "bench_orion did not report every benchmark"
import json, sys
runs = json.load(open(sys.argv[1]))["benchmarks"]
bad = [b["name"] for b in runs if b.get("error_occurred") or not b.get("iterations")]
print("bench_orion: %d of %s benchmarks ran" % (len(runs), sys.argv[2]))
sys.exit(1 if bad or len(runs) != int(sys.argv[2]) else 0)
PY

# The recorder: one second at 10,000 packets/s, every packet written.
"$build/tests/bench/record/bench_record" --rate 10000 --seconds 1 --dir "$out" | tee "$out/record"
grep -Eq 'with recording: .*\([1-9][0-9]* packets, 0 dropped' "$out/record" ||
    fail "bench_record did not record every packet (see above)"
echo "bench.sh --smoke: ok"
