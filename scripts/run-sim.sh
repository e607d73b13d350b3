#!/usr/bin/env bash
# The README's first command: install what is missing, build the release binaries and run
# gimbald on its embedded simulated gimbal (`gimbald --sim`), with config/sim.json's `http`
# section (the operator console at http://127.0.0.1:8761/) and `terrain` section: the
# simulator's terrain, written here by `gimbal-sim --write-dem` as build/release/sim-dem.tif,
# and `video` section: the simulated Orion's H.264 + KLV relayed to udp://127.0.0.1:15010.
# Extra arguments go to gimbald, e.g. `scripts/run-sim.sh orion,viewpro` or
# `scripts/run-sim.sh --log-format text`. In another terminal:
#   build/release/tools/gimbalctl elevation 45.7 -121.5
#   build/release/tools/gimbalctl locate 0.5 -0.3
#   build/release/tools/gimbalctl point 0.5 -0.3 --stare
#   ffplay -fflags nobuffer udp://127.0.0.1:15010      (the video; gimbalctl klv: its KLV)
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs" --target gimbald gimbalctl gimbal-sim
# The DEM config/sim.json names (relative to this directory), again when gimbal-sim changed.
dem=build/release/sim-dem.tif
if [ ! -s "$dem" ] || [ build/release/tools/gimbal-sim -nt "$dem" ]; then
  build/release/tools/gimbal-sim --write-dem "$dem" >&2
fi

sim_arg=()
if [ $# -gt 0 ] && [[ "$1" != -* ]]; then
  sim_arg=("$1")  # a protocol list such as orion,viewpro
  shift
fi
echo "gimbald --sim ${sim_arg[*]:-} on udp://127.0.0.1:8760 - stop with Ctrl-C" >&2
echo "operator console: http://127.0.0.1:8761/  (metrics: /metrics, health: /healthz)" >&2
echo "video with KLV: ffplay -fflags nobuffer udp://127.0.0.1:15010" >&2
# --sim replaces the file's gimbals; the file brings the http section.
exec build/release/daemon/gimbald --sim "${sim_arg[@]}" -c config/sim.json "$@"
