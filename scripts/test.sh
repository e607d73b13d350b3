#!/usr/bin/env bash
# The README's test command: install what is missing, build from scratch with warnings as
# errors, run every test through ctest and list every skipped test (scripts/list-skipped.py),
# build and check the amd64 .deb, then give each fuzz target a short run when clang is
# installed. Usage: scripts/test.sh [--fuzz-seconds N]. With CI=true in the environment a
# test whose tools cannot be had fails instead of being skipped.
#
# The release package and the clang fuzz build are built while ctest runs, at the lowest CPU
# priority (nice 19): ctest's integration tests run one at a time and leave most of the
# machine idle, and at nice 19 a compiler gets a CPU only when a test does not want it, so
# timing-bound tests see the machine as before (docs/operations.md "Test run time").
set -euo pipefail
cd "$(dirname "$0")/.."

fuzz_seconds=${FUZZ_SECONDS:-5}
while [ $# -gt 0 ]; do
  case "$1" in
    --fuzz-seconds) fuzz_seconds=$2; shift 2 ;;
    *) echo "usage: scripts/test.sh [--fuzz-seconds N]" >&2; exit 2 ;;
  esac
done

# Each phase's wall time, printed as it ends (docs/operations.md "Test run time").
phase_start=$SECONDS
phase() { echo "scripts/test.sh: $1 took $((SECONDS - phase_start)) s (total $SECONDS s)"; phase_start=$SECONDS; }

scripts/install-deps.sh
phase "installing packages"

jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset debug
cmake --build --preset debug -j "$jobs"
phase "the debug build"

# The package and fuzz builds, in the background at nice 19 (their output in build/*.log).
fuzz=0
if command -v clang++ >/dev/null 2>&1 && [ "$fuzz_seconds" -gt 0 ]; then fuzz=1; fi
mkdir -p build
background_builds() {
  scripts/package.sh >build/package-build.log 2>&1 || { echo package >build/background-failed; return 1; }
  if [ "$fuzz" -eq 1 ]; then
    { cmake --preset fuzz >/dev/null && cmake --build --preset fuzz -j "$jobs"; } \
      >build/fuzz-build.log 2>&1 || { echo fuzz >build/background-failed; return 1; }
  fi
}
rm -f build/background-failed
# In a process group of its own (setsid) so that a failed or interrupted run stops it too.
# setsid also starts a new scheduler autogroup, and the kernel shares the CPUs between
# autogroups before it looks at nice: the group itself is set to nice 19 (where
# /proc/self/autogroup exists), or the builds would take half the machine from ctest.
setsid nice -n 19 bash -c "{ echo 19 >/proc/self/autogroup; } 2>/dev/null || true
  $(declare -f background_builds); fuzz=$fuzz jobs=$jobs background_builds" &
builds=$!
trap 'kill -- -"$builds" 2>/dev/null || true' EXIT

# Every run ends by listing what was skipped - whole tests (exit 77: a tool could not be had)
# and test cases skipped inside passing tests - whether ctest passed or not: lost coverage is
# said aloud (with CI=true a missing tool fails its test instead: tests/integration/skip.sh).
junit="$PWD/build/debug/ctest-junit.xml"
rm -f "$junit"
status=0
ctest --preset debug -j "$jobs" --output-junit "$junit" || status=$?
phase "ctest"
python3 scripts/list-skipped.py "$junit" || true
if [ "$status" -ne 0 ]; then
  echo "scripts/test.sh: ctest failed (exit $status)" >&2
  exit "$status"
fi

echo "scripts/test.sh: waiting for the package and fuzz builds (build/package-build.log, build/fuzz-build.log)"
if ! wait "$builds"; then
  failed=$(cat build/background-failed 2>/dev/null || echo "background")
  echo "scripts/test.sh: the $failed build failed:" >&2
  tail -n 40 "build/$failed-build.log" >&2 || true
  exit 1
fi
phase "waiting for the package and fuzz builds"

# The amd64 Debian package (a release build in build/package-amd64): lintian, control
# fields, contents, and the programs run from the unpacked package.
deb=$(tail -n 1 build/package-build.log)
tests/package/check-package.sh "$deb"
phase "the package check"

if [ "$fuzz" -eq 1 ]; then
  scripts/fuzz.sh "$fuzz_seconds"
  phase "the fuzz runs"
fi
