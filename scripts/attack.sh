#!/usr/bin/env bash
# The attack suite of issue 25 (docs/operations.md "Attack suite"; tests/soak/attack.py): every
# attack on untrusted input - huge and hostile KLV, TS and H.264 on the video input, hostile
# DEMs, a malicious RTSP camera, MAVLink junk and floods, log floods, hostile configuration
# files - each against a fresh gimbald whose simulated Orion's laser fires under a 2 s
# dead-man; one row per attack (cease-fire delay, ping p50/p99/max, RSS, verdict).
#   scripts/attack.sh [--brief | --seconds N] [--only REGEX] [--json FILE] [--keep] [--list]
# --brief: every attack shortened (about 90 s in all; what ctest runs); default 10 s each.
# Uses the binaries named by GIMBALD, GIMBALCTL and GIMBAL_SIM when set (ctest sets them), else
# builds the release preset (figures belong to a release build). Exit 1 when an attack fails.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${GIMBALD:-}" ] || [ -z "${GIMBAL_SIM:-}" ]; then
  cmake --preset release >/dev/null
  cmake --build --preset release --target gimbald gimbalctl gimbal-sim -j "$(nproc)"
  export GIMBALD=build/release/daemon/gimbald GIMBALCTL=build/release/tools/gimbalctl \
         GIMBAL_SIM=build/release/tools/gimbal-sim
fi
# Debian's interpreter: the suite needs only the standard library, but the pyenv shim that
# may stand first on PATH is not always there for ctest.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
exec "$python" tests/soak/attack.py "$@"
