#!/usr/bin/env bash
# Builds gimbald, gimbal-sim and the latency benchmark in release mode and runs the daemon
# benchmarks (docs/operations.md, "Daemon benchmarks"): command latency (JSON geopoint, and a
# MAVLink DO_GIMBAL_MANAGER_PITCHYAW through the gimbal manager at 100 commands/s), load (CPU,
# RSS) with 16 subscribers, plain and as delta streams (changes: true), the size of STATE
# datagrams and of delta-stream patches, and 50 WebSocket clients of /api/stream at 2 Hz for
# 60 s (every message received? CPU, RSS).
# Timings are not tests: a missed target is only reported. A run that loses something (a
# command, a STATE, a WebSocket message) fails, though: its figures would describe another
# run. The script then still runs the rest and exits 1 with the names of the failed parts.
#
#   --smoke     a few seconds each, as ctest's "bench: bench-daemon.sh --smoke" runs it: every
#               benchmark must run and lose nothing; timings are printed, never checked
#   --no-build  use the programs already built in BUILD_DIR
#
# Environment:
#   BUILD_DIR     an already configured build directory to use instead of the `release`
#                 preset's build/release
#   JOBS          parallel build jobs (default: nproc)
#   LATENCY_ARGS  extra arguments for bench_daemon_latency, e.g. "--count 20000 --poll busy"
#   MAVLINK_ARGS  extra arguments for its --mavlink run (default 3000 commands at 100/s)
#   LOAD_ARGS     extra arguments for load_bench.py (both runs), e.g. "--window 60"
#   SIZE_ARGS     extra arguments for state_size.py, e.g. "--window 120"
#   WS_ARGS       extra arguments for ws_bench.py, e.g. "--clients 100 --window 30"
set -euo pipefail
cd "$(dirname "$0")/.."
smoke=false
build_it=true
for arg in "$@"; do
    case "$arg" in
        --smoke) smoke=true ;;
        --no-build) build_it=false ;;
        *) echo "usage: scripts/bench-daemon.sh [--smoke] [--no-build]" >&2; exit 2 ;;
    esac
done
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
if [[ -n "${BUILD_DIR:-}" ]]; then
    build=$BUILD_DIR
else
    cmake --preset release >/dev/null
    build=build/release
fi
$build_it && cmake --build "$build" --target gimbald gimbal-sim bench_daemon_latency -j "$jobs"

gimbald=$build/daemon/gimbald
sim=$build/tools/gimbal-sim
latency=$build/tests/bench/daemon/bench_daemon_latency
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

if $smoke; then
    latency_args=(--count 1000 --rate 1000)  # past the default rate limit's burst of 400
    mavlink_args=(--count 100 --rate 100)
    load_args=(--warmup 1 --window 2 --stagger 0.5 --check)
    size_args=(--settle 1 --window 2 --check)
    ws_args=(--clients 5 --stagger 0.2 --warmup 1 --window 2 --check)
else
    latency_args=()
    mavlink_args=(--count 3000)
    load_args=()
    size_args=()
    ws_args=(--check)
fi

failed=()
# run NAME COMMAND...: its output to the terminal and $out/NAME; a failure is remembered.
run() {
    local name=$1
    shift
    echo "== $name (load average $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores)"
    if ! "$@" 2>&1 | tee "$out/$name"; then
        failed+=("$name")
        echo "!! $name FAILED"
    fi
    echo
}

# shellcheck disable=SC2086  # the extra arguments are meant to split
run latency "$latency" --gimbald "$gimbald" "${latency_args[@]}" ${LATENCY_ARGS:-}
# shellcheck disable=SC2086
run mavlink "$latency" --gimbald "$gimbald" --mavlink --rate 100 "${mavlink_args[@]}" \
    ${MAVLINK_ARGS:-}
# shellcheck disable=SC2086
run load python3 tests/bench/daemon/load_bench.py --gimbald "$gimbald" --gimbal-sim "$sim" \
    "${load_args[@]}" ${LOAD_ARGS:-}
# shellcheck disable=SC2086
run load-changes python3 tests/bench/daemon/load_bench.py --gimbald "$gimbald" \
    --gimbal-sim "$sim" --changes --ttl 60 "${load_args[@]}" ${LOAD_ARGS:-}
# shellcheck disable=SC2086
run size python3 tests/bench/daemon/state_size.py --gimbald "$gimbald" "${size_args[@]}" \
    ${SIZE_ARGS:-}
# shellcheck disable=SC2086
run ws python3 tests/bench/http/ws_bench.py --gimbald "$gimbald" --gimbal-sim "$sim" \
    "${ws_args[@]}" ${WS_ARGS:-}

# key=value pairs of a RESULT line
value() { grep '^RESULT' "$out/$2" 2>/dev/null | tr ' ' '\n' | sed -n "s/^$1=//p"; }
total() { echo $(( $(value count "$1" || echo 0) + $(value lost "$1" || echo 0) )); }
echo "== summary"
printf '  latency  p50 %s us, p99 %s us (target < 200), p99.9 %s us, max %s us, lost %s of %s\n' \
    "$(value p50_us latency)" "$(value p99_us latency)" "$(value p999_us latency)" \
    "$(value max_us latency)" "$(value lost latency)" "$(total latency)"
printf '  mavlink  p50 %s us, p99 %s us (target < 300), max %s us, lost %s of %s (PITCHYAW -> OrionCmd, 100/s)\n' \
    "$(value p50_us mavlink)" "$(value p99_us mavlink)" "$(value max_us mavlink)" \
    "$(value lost mavlink)" "$(total mavlink)"
printf '  load     CPU %s %% of a core (target < 1), VmRSS %s kB, VmHWM %s kB (target < 20480)\n' \
    "$(value cpu_pct load)" "$(value rss_kb load)" "$(value hwm_kb load)"
printf '  changes  CPU %s %% of a core (target <= 0.6), VmHWM %s kB (16 delta subscribers)\n' \
    "$(value cpu_pct load-changes)" "$(value hwm_kb load-changes)"
printf '  size     full STATE %s B, telemetry-only %s B (target <= 1200); patches: %s %% fit 1472 B (target 95), median %s B, max %s B\n' \
    "$(value full_bytes size)" "$(value telemetry_bytes size)" "$(value patch_fit_pct size)" \
    "$(value patch_median_bytes size)" "$(value patch_max_bytes size)"
printf '  ws       %s clients at 2 Hz: every message %s (min %s of %s), CPU %s %% of a core (target < 3), VmHWM %s kB (target < 30720)\n' \
    "$(value clients ws)" "$(value complete ws)" "$(value min_states ws)" \
    "$(value expected ws)" "$(value cpu_pct ws)" "$(value hwm_kb ws)"
if [[ ${#failed[@]} -gt 0 ]]; then
    echo "bench-daemon.sh: FAILED: ${failed[*]} (lost or refused something; see above)" >&2
    exit 1
fi
$smoke && echo "bench-daemon.sh --smoke: ok"
exit 0
