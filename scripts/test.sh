#!/usr/bin/env bash
# The README's test command: install what is missing, build from scratch with warnings as
# errors, run every test through ctest and list every skipped test (scripts/list-skipped.py),
# build and check the amd64 .deb, then give each fuzz target a short run when clang is
# installed. Usage: scripts/test.sh [--fuzz-seconds N]. With CI=true in the environment a
# test whose tools cannot be had fails instead of being skipped.
set -euo pipefail
cd "$(dirname "$0")/.."

fuzz_seconds=${FUZZ_SECONDS:-5}
while [ $# -gt 0 ]; do
  case "$1" in
    --fuzz-seconds) fuzz_seconds=$2; shift 2 ;;
    *) echo "usage: scripts/test.sh [--fuzz-seconds N]" >&2; exit 2 ;;
  esac
done

scripts/install-deps.sh

jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset debug
cmake --build --preset debug -j "$jobs"
# Every run ends by listing what was skipped - whole tests (exit 77: a tool could not be had)
# and test cases skipped inside passing tests - whether ctest passed or not: lost coverage is
# said aloud (with CI=true a missing tool fails its test instead: tests/integration/skip.sh).
junit="$PWD/build/debug/ctest-junit.xml"
rm -f "$junit"
status=0
ctest --preset debug -j "$jobs" --output-junit "$junit" || status=$?
python3 scripts/list-skipped.py "$junit" || true
if [ "$status" -ne 0 ]; then
  echo "scripts/test.sh: ctest failed (exit $status)" >&2
  exit "$status"
fi

# The amd64 Debian package (a release build in build/package-amd64): lintian, control
# fields, contents, and the programs run from the unpacked package.
deb=$(scripts/package.sh | tail -n 1)
tests/package/check-package.sh "$deb"

if command -v clang++ >/dev/null 2>&1 && [ "$fuzz_seconds" -gt 0 ]; then
  cmake --preset fuzz >/dev/null
  cmake --build --preset fuzz -j "$jobs"
  scripts/fuzz.sh "$fuzz_seconds"
fi
