#!/usr/bin/env bash
# Runs every libFuzzer target built by the `fuzz` preset for N seconds (default 60) each,
# under ASan/UBSan, starting from the committed corpus in tests/fuzz/corpus/<target>.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
status=0
for target in build/fuzz/tests/fuzz/fuzz_*; do
  [ -x "$target" ] || continue
  name=$(basename "$target")
  corpus=tests/fuzz/corpus/${name#fuzz_}
  work=$(mktemp -d)
  [ -d "$corpus" ] && cp -r "$corpus"/. "$work"/ 2>/dev/null || true
  echo "fuzz: $name for ${seconds}s"
  if ! "$target" -max_total_time="$seconds" -print_final_stats=0 -artifact_prefix="build/fuzz/$name-" "$work" \
        >"build/fuzz/$name.log" 2>&1; then
    echo "fuzz: $name FAILED, see build/fuzz/$name.log" >&2
    tail -40 "build/fuzz/$name.log" >&2
    status=1
  fi
  rm -rf "$work"
done
exit $status
