#!/bin/bash
# MAVLink gimbal manager against node-mavlink (an implementation we did not write): the
# QGroundControl sequence, control arbitration, link down, bad input and signing. The npm
# package is pinned by tests/integration/mavlink/package-lock.json and installed with `npm ci`
# when node_modules is missing. Exit 77 (skipped) when Node.js cannot be had.
set -u
here="$(cd "$(dirname "$0")" && pwd)"
dir="$here/mavlink"

# shellcheck source=npm_package.sh
. "$here/npm_package.sh"
need_npm_package "$dir" node-mavlink
: "${GIMBALD:?GIMBALD not set}" "${GIMBAL_SIM:?GIMBAL_SIM not set}"
exec timeout 200 node "$dir/gimbal_manager.js"
