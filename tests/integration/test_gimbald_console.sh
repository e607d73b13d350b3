#!/bin/bash
# The operator console (web/) in Debian's headless chromium, driven by puppeteer-core against
# gimbald with `http` configured and gimbal-sim behind it (console/console_test.js). The npm
# package is pinned by tests/integration/console/package-lock.json and installed with `npm ci`
# when node_modules is missing. Exit 77 (skipped) when Node.js or chromium cannot be had;
# with CI=true it fails instead (skip.sh).
# The screenshot goes to the current directory (ctest: the build tree) or CONSOLE_SCREENSHOT.
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
exec timeout 150 node "$dir/console_test.js"
