#!/usr/bin/env bash
# Runs every libFuzzer target built by the `fuzz` preset for N seconds (default 60) each,
# under ASan/UBSan, starting from the committed seeds (tests/fuzz/corpus/<target> and the
# saved crash inputs in tests/fuzz/regressions/<target>). A crash input is left as
# build/fuzz/<target>-crash-*; copy it into tests/fuzz/regressions/<target>/ once fixed.
#   cmake --preset fuzz && cmake --build --preset fuzz && scripts/fuzz.sh [seconds]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
status=0
found=0
for target in build/fuzz/tests/fuzz/fuzz_*; do
  [ -x "$target" ] || continue
  found=1
  name=$(basename "$target")
  seeds=${name#fuzz_}
  work=$(mktemp -d)
  for dir in tests/fuzz/corpus/$seeds tests/fuzz/regressions/$seeds; do
    [ -d "$dir" ] && cp -r "$dir"/. "$work"/ 2>/dev/null || true
  done
  dict=()
  [ -f "tests/fuzz/$seeds.dict" ] && dict=(-dict="tests/fuzz/$seeds.dict")
  echo "fuzz: $name for ${seconds}s"
  if "$target" -max_total_time="$seconds" -print_final_stats=1 -artifact_prefix="build/fuzz/$name-" \
        "${dict[@]}" "$work" >"build/fuzz/$name.log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "build/fuzz/$name.log" | grep -o '[0-9]*$' || echo '?')
    echo "fuzz: $name ok, $runs runs, corpus $(ls "$work" | wc -l) inputs"
  else
    echo "fuzz: $name FAILED, see build/fuzz/$name.log" >&2
    grep -E '^fuzz_|ERROR|runtime error' "build/fuzz/$name.log" | head -5 >&2 || true
    status=1
  fi
  rm -rf "$work"
done
if [ $found = 0 ]; then
  echo "fuzz: no targets in build/fuzz/tests/fuzz (cmake --preset fuzz && cmake --build --preset fuzz)" >&2
  exit 1
fi
exit $status
