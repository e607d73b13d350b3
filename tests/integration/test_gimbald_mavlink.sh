#!/bin/bash
# MAVLink gimbal manager against node-mavlink (an implementation we did not write): the
# QGroundControl sequence, control arbitration, link down, bad input and signing. The npm
# package is pinned by tests/integration/mavlink/package-lock.json and installed with `npm ci`
# when node_modules is missing. Exit 77 (skipped) when Node.js cannot be had.
set -u
here="$(cd "$(dirname "$0")" && pwd)"
dir="$here/mavlink"

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
if [ ! -d "$dir/node_modules/node-mavlink" ]; then
    if ! (cd "$dir" && npm ci --no-audit --no-fund >/dev/null 2>&1); then
        echo "skip: npm ci failed (no registry access?)"
        exit 77
    fi
fi
: "${GIMBALD:?GIMBALD not set}" "${GIMBAL_SIM:?GIMBAL_SIM not set}"
exec timeout 200 node "$dir/gimbal_manager.js"
