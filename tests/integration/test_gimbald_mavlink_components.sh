#!/bin/bash
# Two gimbals through the MAVLink gimbal manager, one manager component each (contract
# section 14), driven by node-mavlink the way MAVSDK's Gimbal plugin matches gimbals (by the
# sender's component id). The npm package is pinned by tests/integration/mavlink/
# package-lock.json and installed with `npm ci` when node_modules is missing. Exit 77
# (skipped) when Node.js cannot be had.
set -u
here="$(cd "$(dirname "$0")" && pwd)"
dir="$here/mavlink"

# shellcheck source=npm_package.sh
. "$here/npm_package.sh"
need_npm_package "$dir" node-mavlink
: "${GIMBALD:?GIMBALD not set}" "${GIMBAL_SIM:?GIMBAL_SIM not set}"
exec timeout 120 node "$dir/two_gimbals.js"
