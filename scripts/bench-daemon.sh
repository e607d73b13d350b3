#!/usr/bin/env bash
# Builds gimbald, gimbal-sim and the latency benchmark in release mode and runs the daemon
# benchmarks (docs/operations.md, "Daemon benchmarks"): command latency (JSON geopoint, and a
# MAVLink DO_GIMBAL_MANAGER_PITCHYAW through the gimbal manager at 100 commands/s), load (CPU,
# RSS) with 16 subscribers, plain and as delta streams (changes: true), the size of STATE
# datagrams and of delta-stream patches, and 50 WebSocket clients of /api/stream at 2 Hz for
# 60 s (every message received? CPU, RSS).
# Timings are not tests: a missed target is reported as MISSED (in each part and in the
# summary, which never says "ok" beside one) but does not fail the run. A run that loses
# something (a command, a STATE, a WebSocket message) fails, though: its figures would
# describe another run. The script then still runs the rest and exits 1 with the names of
# the failed parts. Memory targets are on anonymous memory (RssAnon: the daemon's own heap
# and stacks); VmRSS, mostly the pages of shared libraries, is printed beside it.
#
#   --smoke     the same configuration (clients, subscribers, rates), a few seconds each, as
#               ctest's "bench: bench-daemon.sh --smoke" runs it: every benchmark must run
#               and lose nothing; timings and sizes are printed with their verdicts
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

# Smoke and full runs differ only in how long they measure (counts at the same rate,
# windows), never in what they set up.
if $smoke; then
    latency_args=(--count 1000)
    mavlink_args=(--count 100)
    load_args=(--warmup 1 --window 2 --check)
    size_args=(--window 2 --check)
    ws_args=(--warmup 1 --window 2 --check)
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
# below VALUE LIMIT / at_most VALUE LIMIT: yes or no (decimals allowed), empty without a value.
below() { [[ -n "$1" ]] && awk -v v="$1" -v l="$2" 'BEGIN { print (v < l) ? "yes" : "no" }'; }
at_most() { [[ -n "$1" && -n "$2" ]] && awk -v v="$1" -v l="$2" 'BEGIN { print (v <= l) ? "yes" : "no" }'; }
# judge NAME OK: the verdict of one target in verdict[NAME]: "met", "MISSED" (also listed in
# `missed`), or "?" when the part printed no figure (it failed, see above).
declare -A verdict
missed=()
judge() {
    if [[ -z "$2" ]]; then
        verdict[$1]="?"
    elif [[ "$2" == yes ]]; then
        verdict[$1]=met
    else
        verdict[$1]=MISSED
        missed+=("$1")
    fi
}
judge latency-p99 "$(below "$(value p99_us latency)" 200)"
judge mavlink-p99 "$(below "$(value p99_us mavlink)" 300)"
judge load-cpu "$(value cpu_met load)"
judge load-memory "$(value anon_met load)"
judge changes-cpu "$(value cpu_met load-changes)"
judge changes-memory "$(value anon_met load-changes)"
judge size-full "$(at_most "$(value full_bytes size)" 9000)"
judge size-telemetry "$(at_most "$(value telemetry_bytes size)" 1200)"
judge size-signed "$(at_most "$(value telemetry_signed_bytes size)" 1472)"
judge size-patches "$(at_most 99 "$(value patch_fit_pct size)")"
judge ws-cpu "$(value cpu_met ws)"
judge ws-memory "$(value anon_met ws)"
echo "== summary"
printf '  latency  p50 %s us, p99 %s us (target < 200: %s), p99.9 %s us, max %s us, lost %s of %s\n' \
    "$(value p50_us latency)" "$(value p99_us latency)" "${verdict[latency-p99]}" \
    "$(value p999_us latency)" "$(value max_us latency)" "$(value lost latency)" "$(total latency)"
printf '  mavlink  p50 %s us, p99 %s us (target < 300: %s), max %s us, lost %s of %s (PITCHYAW -> OrionCmd, 100/s)\n' \
    "$(value p50_us mavlink)" "$(value p99_us mavlink)" "${verdict[mavlink-p99]}" \
    "$(value max_us mavlink)" "$(value lost mavlink)" "$(total mavlink)"
printf '  load     CPU %s %% of a core (target < 1: %s), anonymous memory %s kB (target < 20480: %s), VmRSS %s kB (file-backed %s kB), Pss %s kB\n' \
    "$(value cpu_pct load)" "${verdict[load-cpu]}" "$(value anon_kb load)" \
    "${verdict[load-memory]}" "$(value rss_kb load)" "$(value file_kb load)" "$(value pss_kb load)"
printf '  changes  CPU %s %% of a core (target <= 0.6: %s), anonymous memory %s kB (target < 20480: %s) (16 delta subscribers)\n' \
    "$(value cpu_pct load-changes)" "${verdict[changes-cpu]}" \
    "$(value anon_kb load-changes)" "${verdict[changes-memory]}"
printf '  size     full STATE %s B (target <= 9000: %s), telemetry-only %s B (target <= 1200: %s), signed %s B (target <= 1472: %s)\n' \
    "$(value full_bytes size)" "${verdict[size-full]}" "$(value telemetry_bytes size)" \
    "${verdict[size-telemetry]}" "$(value telemetry_signed_bytes size)" "${verdict[size-signed]}"
printf '  patches  %s %% fit 1472 B (target >= 99: %s), median %s B, max %s B\n' \
    "$(value patch_fit_pct size)" "${verdict[size-patches]}" \
    "$(value patch_median_bytes size)" "$(value patch_max_bytes size)"
printf '  ws       %s clients at 2 Hz: every message %s (min %s of %s), CPU %s %% of a core (target < 3: %s), anonymous memory %s kB (target < 30720: %s), VmRSS %s kB\n' \
    "$(value clients ws)" "$(value complete ws)" "$(value min_states ws)" \
    "$(value expected ws)" "$(value cpu_pct ws)" "${verdict[ws-cpu]}" \
    "$(value anon_kb ws)" "${verdict[ws-memory]}" "$(value rss_kb ws)"
if [[ ${#missed[@]} -gt 0 ]]; then
    echo "  targets MISSED: ${missed[*]}"
fi
if [[ ${#failed[@]} -gt 0 ]]; then
    echo "bench-daemon.sh: FAILED: ${failed[*]} (lost or refused something; see above)" >&2
    exit 1
fi
if [[ ${#missed[@]} -gt 0 ]]; then
    echo "bench-daemon.sh$($smoke && echo " --smoke"): nothing lost, but ${#missed[@]} target(s) MISSED: ${missed[*]}"
else
    echo "bench-daemon.sh$($smoke && echo " --smoke"): nothing lost, every target met"
fi
exit 0
