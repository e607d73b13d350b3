#!/bin/bash
# The MAVLink camera component (contract section 16) as QGroundControl's camera manager sees
# it: discovery, the stream URI opened with ffprobe, click-to-track on the simulated Orion
# (tests/integration/mavlink/camera.js, node-mavlink pinned by package-lock.json and installed
# with `npm ci` when node_modules is missing). Exit 77 (skipped) when Node.js or ffprobe cannot
# be had (with CI=true: fails, skip.sh).
set -u
here="$(cd "$(dirname "$0")" && pwd)"
dir="$here/mavlink"

# shellcheck source=npm_package.sh
. "$here/npm_package.sh"
need_npm_package "$dir" node-mavlink
if ! command -v ffprobe >/dev/null; then
    skip_test "ffprobe not installed (apt-get install ffmpeg)"
fi
: "${GIMBALD:?GIMBALD not set}" "${GIMBAL_SIM:?GIMBAL_SIM not set}"
exec timeout 180 node "$dir/camera.js"
