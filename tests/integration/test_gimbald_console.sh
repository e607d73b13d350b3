#!/bin/bash
# The operator console (web/) in Debian's headless chromium, driven by puppeteer-core against
# gimbald with `http` configured and gimbal-sim behind it (console/console_test.js). The npm
# package is pinned by tests/integration/console/package-lock.json and installed with `npm ci`
# when node_modules is missing. Exit 77 (skipped) when Node.js or chromium cannot be had.
# The screenshot goes to the current directory (ctest: the build tree) or CONSOLE_SCREENSHOT.
set -u
here="$(cd "$(dirname "$0")" && pwd)"
dir="$here/console"

if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    # Debian's nodejs and npm (scripts/install-deps.sh installs them on a CI machine).
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        apt-get install -y --no-install-recommends nodejs npm >/dev/null 2>&1
    elif command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
        sudo -n apt-get install -y --no-install-recommends nodejs npm >/dev/null 2>&1
    fi
fi
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    echo "skip: node and npm not installed (apt-get install nodejs npm)"
    exit 77
fi
CHROMIUM="${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}"
if [ -z "$CHROMIUM" ]; then
    echo "skip: chromium not installed (apt-get install chromium)"
    exit 77
fi
export CHROMIUM
if [ ! -d "$dir/node_modules/puppeteer-core" ]; then
    if ! (cd "$dir" && npm ci --no-audit --no-fund >/dev/null 2>&1); then
        echo "skip: npm ci failed (no registry access?)"
        exit 77
    fi
fi
: "${GIMBALD:?GIMBALD not set}" "${GIMBAL_SIM:?GIMBAL_SIM not set}"
exec timeout 150 node "$dir/console_test.js"
