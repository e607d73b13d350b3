#!/bin/bash
# The console's video panel (contract section 18) in Debian's headless chromium, driven by
# puppeteer-core against gimbald with an in-process simulated Orion and its video
# (console/console_video_test.js): decoding, click-to-point on a landmark, zoom, keys,
# layouts, visual tracking (drag a box, alt+click, Esc; when gimbal-track is found: GIMBAL_TRACK
# or beside gimbald), reconnect; prints glass-to-glass latency figures (not checked here:
# scripts/bench-console-video.sh). Exit 77 (skipped) when Node.js or chromium cannot be had
# (with CI=true it fails instead: skip.sh).
# The screenshot goes to the current directory (ctest: the build tree) or
# CONSOLE_VIDEO_SCREENSHOT.
set -u
here="$(cd "$(dirname "$0")" && pwd)"
dir="$here/console"

# shellcheck source=npm_package.sh
. "$here/npm_package.sh"
CHROMIUM="${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}"
if [ -z "$CHROMIUM" ]; then
    skip_test "chromium not installed (apt-get install chromium)"
fi
export CHROMIUM
need_npm_package "$dir" puppeteer-core
: "${GIMBALD:?GIMBALD not set}" "${GIMBAL_SIM:?GIMBAL_SIM not set}"
exec timeout 240 node "$dir/console_video_test.js"
