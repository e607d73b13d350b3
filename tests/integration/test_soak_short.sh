#!/usr/bin/env bash
# The 20-second version of scripts/soak.sh: link flaps, junk, subscriber churn, invalid and
# badly signed requests, dead-man laser fires; every reply arrives, every fire is ceased.
set -uo pipefail
src=${GIMBAL_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
# shellcheck source=skip.sh
. "$(dirname "$0")/skip.sh"
if [ -z "${GIMBALD:-}" ] || [ -z "${GIMBALCTL:-}" ] || [ -z "${GIMBAL_SIM:-}" ]; then
  skip_test "GIMBALD, GIMBALCTL or GIMBAL_SIM not set"
fi
exec "$src/scripts/soak.sh" --seconds 20
