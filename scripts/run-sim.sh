#!/usr/bin/env bash
# The README's first command: install what is missing, build the release binaries and run
# gimbald on its embedded simulated gimbal (`gimbald --sim`), with config/sim.json's `http`
# section: the operator console at http://127.0.0.1:8761/. Extra arguments go to gimbald,
# e.g. `scripts/run-sim.sh orion,viewpro` or `scripts/run-sim.sh --log-format text`.
# In another terminal: build/release/tools/gimbalctl geopoint 45.7 -121.5 300 --stare
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs" --target gimbald gimbalctl gimbal-sim

sim_arg=()
if [ $# -gt 0 ] && [[ "$1" != -* ]]; then
  sim_arg=("$1")  # a protocol list such as orion,viewpro
  shift
fi
echo "gimbald --sim ${sim_arg[*]:-} on udp://127.0.0.1:8760 - stop with Ctrl-C" >&2
echo "operator console: http://127.0.0.1:8761/  (metrics: /metrics, health: /healthz)" >&2
# --sim replaces the file's gimbals; the file brings the http section.
exec build/release/daemon/gimbald --sim "${sim_arg[@]}" -c config/sim.json "$@"
