#!/usr/bin/env bash
# Builds gimbald, gimbal-sim and the latency benchmark in release mode and runs the daemon
# benchmarks (docs/operations.md, "Daemon benchmarks"): command latency (JSON geopoint, and a
# MAVLink DO_GIMBAL_MANAGER_PITCHYAW through the gimbal manager at 100 commands/s), load (CPU,
# RSS), the size of STATE datagrams, and 50 WebSocket clients of /api/stream at 2 Hz for 60 s
# (every message received? CPU, RSS).
# Timings, not tests: nothing here fails on a missed target, it only says so.
#
# Environment:
#   BUILD_DIR     an already configured release build directory to use instead of the
#                 `release` preset's build/release
#   JOBS          parallel build jobs (default: nproc)
#   LATENCY_ARGS  extra arguments for bench_daemon_latency, e.g. "--count 20000 --poll busy"
#   MAVLINK_ARGS  extra arguments for its --mavlink run (default 3000 commands at 100/s)
#   LOAD_ARGS     extra arguments for load_bench.py, e.g. "--window 60"
#   WS_ARGS       extra arguments for ws_bench.py, e.g. "--clients 100 --window 30"
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
if [[ -n "${BUILD_DIR:-}" ]]; then
    build=$BUILD_DIR
else
    cmake --preset release >/dev/null
    build=build/release
fi
cmake --build "$build" --target gimbald gimbal-sim bench_daemon_latency -j "$jobs"

gimbald=$build/daemon/gimbald
sim=$build/tools/gimbal-sim
latency=$build/tests/bench/daemon/bench_daemon_latency
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "== latency (load average $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores)"
# shellcheck disable=SC2086  # the extra arguments are meant to split
"$latency" --gimbald "$gimbald" ${LATENCY_ARGS:-} | tee "$out/latency"
echo
echo "== MAVLink latency (load average $(cut -d' ' -f1-3 /proc/loadavg))"
# shellcheck disable=SC2086
"$latency" --gimbald "$gimbald" --mavlink --rate 100 --count 3000 ${MAVLINK_ARGS:-} \
    | tee "$out/mavlink"
echo
echo "== load (load average $(cut -d' ' -f1-3 /proc/loadavg))"
# shellcheck disable=SC2086
python3 tests/bench/daemon/load_bench.py --gimbald "$gimbald" --gimbal-sim "$sim" \
    ${LOAD_ARGS:-} | tee "$out/load"
echo
echo "== STATE size (full, and subscribe keys=[telemetry])"
python3 tests/bench/daemon/state_size.py --gimbald "$gimbald" | tee "$out/size"
echo
echo "== WebSocket stream (load average $(cut -d' ' -f1-3 /proc/loadavg))"
# shellcheck disable=SC2086
python3 tests/bench/http/ws_bench.py --gimbald "$gimbald" --gimbal-sim "$sim" ${WS_ARGS:-} \
    | tee "$out/ws"

# key=value pairs of a RESULT line
value() { grep '^RESULT' "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
echo
echo "== summary"
printf '  latency  p50 %s us, p99 %s us (target < 200), p99.9 %s us, max %s us, lost %s of %s\n' \
    "$(value p50_us "$out/latency")" "$(value p99_us "$out/latency")" \
    "$(value p999_us "$out/latency")" "$(value max_us "$out/latency")" \
    "$(value lost "$out/latency")" \
    "$(( $(value count "$out/latency") + $(value lost "$out/latency") ))"
printf '  mavlink  p50 %s us, p99 %s us (target < 300), max %s us, lost %s of %s (PITCHYAW -> OrionCmd, 100/s)\n' \
    "$(value p50_us "$out/mavlink")" "$(value p99_us "$out/mavlink")" \
    "$(value max_us "$out/mavlink")" "$(value lost "$out/mavlink")" \
    "$(( $(value count "$out/mavlink") + $(value lost "$out/mavlink") ))"
printf '  load     CPU %s %% of a core (target < 1), VmRSS %s kB, VmHWM %s kB (target < 20480)\n' \
    "$(value cpu_pct "$out/load")" "$(value rss_kb "$out/load")" "$(value hwm_kb "$out/load")"
printf '  ws       %s clients at 2 Hz: every message %s (min %s of %s), CPU %s %% of a core (target < 3), VmHWM %s kB (target < 30720)\n' \
    "$(value clients "$out/ws")" "$(value complete "$out/ws")" "$(value min_states "$out/ws")" \
    "$(value expected "$out/ws")" "$(value cpu_pct "$out/ws")" "$(value hwm_kb "$out/ws")"
