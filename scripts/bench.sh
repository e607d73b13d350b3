#!/usr/bin/env bash
# Builds the benchmarks with the `release` preset and runs them: the Orion codec (bench_orion),
# MISB ST 0601 KLV generation and decoding (bench_klv), the video relay: a 1080p30 8 Mbit/s
# H.264 TS with KLV from a UDP input to two UDP outputs (bench_video_relay, CPU and latency,
# docs/video.md "Relay budget"; VIDEO_SECONDS sets its length, default 10), one ray-terrain
# intersection on a 1 arc-second model (bench_terrain, docs/terrain.md "Cost"; the model is
# kept in the build tree), the simulated camera's render + encode at 640x360 15 fps
# (bench_sim_video, docs/simulator.md "Cost"), the recorder at 10,000 packets/s
# (bench_record, docs/operations.md "Recording throughput"; RECORD_SECONDS, default 60), then
# visual tracking: gimbal-track decoding and tracking at the input rate, CSRT and KCF, 640x360
# at 15 fps and 1280x720 at 30 fps (bench_track, docs/tracking.md "Cost"; TRACK_SECONDS sets
# each run's length, default 20), and tracking with the daemon: frame received -> steering
# command sent and the laser dead-man while tracking, real gimbal-sim + gimbald + gimbal-track
# (tests/bench/track/track_latency_bench.py, docs/tracking.md "Cost"; TRACK_LATENCY_SECONDS
# sets how long the track runs, default 60).
# Extra arguments go to each Google Benchmark program, bench_terrain and bench_sim_video, e.g.
#   scripts/bench.sh --benchmark_filter=Decode --benchmark_repetitions=5
# Each target is printed as met or MISSED (a summary at the end); timings are never enforced.
#
#   --smoke     the same benchmarks on the same data and models, each measured briefly (the
#               relay 2 s, the recorder 1 s, each tracking run 3 s, the track with gimbald 8 s);
#               fails when one does not run or loses something. ctest runs it as "bench:
#               bench.sh --smoke" (with TRACK_LATENCY_SMOKE=0: the tracking latency smoke is a
#               ctest of its own, "bench: track_latency_bench.py --smoke").
#   --no-build  use the programs already built in BUILD_DIR
#
# Environment: BUILD_DIR, an already configured build directory instead of build/release;
# JOBS, parallel build jobs (default: nproc).
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
targets=(bench_orion bench_klv bench_terrain bench_video_relay bench_sim_video bench_record
         bench_track gimbal-track gimbald gimbal-sim)
$build_it && cmake --build "$build" --target "${targets[@]}" -j "$jobs"
bench=$build/tests/bench
model_dir=$bench/terrain  # the terrain model, built once and kept
track_latency=(python3 tests/bench/track/track_latency_bench.py --gimbald "$build/daemon/gimbald"
               --gimbal-sim "$build/tools/gimbal-sim" --gimbal-track "$build/tools/gimbal-track")

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "bench.sh$($smoke && echo " --smoke"): FAILED: $*" >&2; exit 1; }
missed=()
# verdicts FILE: the "target ...: met/MISSED" lines of a program's output, shown and counted.
verdicts() {
    local line
    while IFS= read -r line; do
        echo "  $line"
        if [[ $line == *MISSED* ]]; then missed+=("$line"); fi
    done < <(grep -E 'target.*(met|MISSED)' "$1" || true)
}

if ! $smoke; then
    for program in bench_orion bench_klv; do
        "$bench/$program" --benchmark_out="$out/$program.json" --benchmark_out_format=json \
            ${args[@]+"${args[@]}"}
    done
    "$bench/video/bench_video_relay" --seconds "${VIDEO_SECONDS:-10}" --dir "$bench/video" |
        tee "$out/video"
    "$bench/terrain/bench_terrain" --model-dir "$model_dir" ${args[@]+"${args[@]}"} |
        tee "$out/terrain"
    "$bench/sim_video/bench_sim_video" ${args[@]+"${args[@]}"}
    "$bench/record/bench_record" --rate 10000 --seconds "${RECORD_SECONDS:-60}" --dir "$out" |
        tee "$out/record"
    "$bench/track/bench_track" --seconds "${TRACK_SECONDS:-20}" | tee "$out/track"
    "${track_latency[@]}" --seconds "${TRACK_LATENCY_SECONDS:-60}" | tee "$out/track_latency"
else
    # Every registered Google benchmark must run and report; none may flag an error.
    for program in bench_orion bench_klv; do
        expected=$("$bench/$program" --benchmark_list_tests | wc -l)
        "$bench/$program" --benchmark_min_time=0.01 --benchmark_format=json \
            >"$out/$program.json" 2>"$out/$program.err" ||
            fail "$program exited $?: $(cat "$out/$program.err")"
        python3 - "$out/$program.json" "$expected" "$program" <<'PY' ||
import json, sys
runs = json.load(open(sys.argv[1]))["benchmarks"]
bad = [b["name"] for b in runs if b.get("error_occurred") or not b.get("iterations")]
print("%s: %d of %s benchmarks ran" % (sys.argv[3], len(runs), sys.argv[2]))
sys.exit(1 if bad or len(runs) != int(sys.argv[2]) else 0)
PY
            fail "$program did not report every benchmark"
    done

    # The video relay exits non-zero when it loses a unit.
    "$bench/video/bench_video_relay" --smoke --dir "$bench/video" >"$out/video" 2>&1 ||
        fail "bench_video_relay --smoke: $(tail -5 "$out/video")"
    echo "bench_video_relay --smoke: ran, nothing lost"

    # The terrain benchmark on the full run's model (built once, kept in the build tree).
    "$bench/terrain/bench_terrain" --smoke --model-dir "$model_dir" >"$out/terrain" 2>&1 ||
        fail "bench_terrain --smoke: $(tail -5 "$out/terrain")"
    echo "bench_terrain --smoke: ran"

    # The simulated camera: a few frames rendered and encoded.
    "$bench/sim_video/bench_sim_video" --smoke >"$out/sim_video" 2>&1 ||
        fail "bench_sim_video --smoke: $(tail -5 "$out/sim_video")"
    echo "bench_sim_video --smoke: ran"

    # The recorder: one second at 10,000 packets/s, every packet written.
    "$bench/record/bench_record" --rate 10000 --seconds 1 --dir "$out" | tee "$out/record"
    grep -Eq 'with recording: .*\([1-9][0-9]* packets, 0 dropped' "$out/record" ||
        fail "bench_record did not record every packet (see above)"

    # Visual tracking, the full run's streams and trackers for 3 s each: gimbal-track answers
    # every run (bench_track exits non-zero when one fails).
    "$bench/track/bench_track" --smoke >"$out/track" 2>&1 ||
        fail "bench_track --smoke: $(tail -5 "$out/track")"
    echo "bench_track --smoke: ran"

    # Tracking with gimbald: a track on the simulator's car for 8 s, the laser left to its
    # dead-man meanwhile; fails without a track, a steering latency in /metrics or a cease.
    if [[ ${TRACK_LATENCY_SMOKE:-1} != 0 ]]; then
        "${track_latency[@]}" --smoke >"$out/track_latency" 2>&1 ||
            fail "track_latency_bench.py --smoke: $(tail -15 "$out/track_latency")"
        echo "track_latency_bench.py --smoke: ran"
    fi
fi

echo "== targets"
python3 scripts/bench-targets.py "$out/bench_orion.json" "$out/bench_klv.json" |
    tee "$out/targets" | grep -v '^RESULT'
while IFS= read -r line; do
    if [[ $line == *MISSED* ]]; then missed+=("$line"); fi
done <"$out/targets"
verdicts "$out/video"
verdicts "$out/terrain"
verdicts "$out/record"
verdicts "$out/track"
if [[ -f $out/track_latency ]]; then verdicts "$out/track_latency"; fi
name="bench.sh$($smoke && echo " --smoke")"
if ((${#missed[@]})); then
    echo "$name: nothing lost, but ${#missed[@]} target(s) MISSED (above)"
else
    echo "$name: nothing lost, every target met"
fi
