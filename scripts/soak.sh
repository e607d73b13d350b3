#!/usr/bin/env bash
# Soak under faults (issue 8, docs/operations.md "Soak test"): gimbald with two flapping
# gimbal-sim Orions, subscriber churn, 200 requests/s (a third invalid or badly signed) and
# dead-man laser fires; a table of RSS, fds, replies and reconnects, and a verdict.
#   scripts/soak.sh [--minutes N | --seconds N]     (default 30 minutes)
# Uses the binaries named by GIMBALD, GIMBALCTL and GIMBAL_SIM when set (ctest sets them),
# else builds the release preset.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=1800
every=60
while [ $# -gt 0 ]; do
  case "$1" in
    --minutes) seconds=$(( $2 * 60 )); shift 2 ;;
    --seconds) seconds=$2; every=5; shift 2 ;;
    *) echo "usage: scripts/soak.sh [--minutes N | --seconds N]" >&2; exit 2 ;;
  esac
done
if [ -z "${GIMBALD:-}" ]; then
  scripts/install-deps.sh
  cmake --preset release >/dev/null
  cmake --build --preset release --target gimbald gimbalctl gimbal-sim -j "$(nproc)"
  export GIMBALD=build/release/daemon/gimbald GIMBALCTL=build/release/tools/gimbalctl \
         GIMBAL_SIM=build/release/tools/gimbal-sim
fi
exec python3 tests/soak/soak.py --seconds "$seconds" --report-every "$every"
