# Sourced by the integration tests that run an npm package (node-mavlink, puppeteer-core):
# `need_npm_package DIR MODULE` makes sure Node.js and npm exist (Debian's, installed when
# running as root or with password-less sudo) and that DIR's pinned packages are installed
# (`npm ci` from its package-lock.json when DIR/node_modules/MODULE is missing). Exits 77
# (skipped) when either cannot be had - with CI=true fails instead (skip.sh). Not a test
# itself (no test_ prefix).

# shellcheck source=skip.sh
. "$(dirname "${BASH_SOURCE[0]}")/skip.sh"

need_npm_package() {
    local dir=$1 module=$2
    if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
        # Debian's nodejs and npm (scripts/install-deps.sh installs them on a CI machine).
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
            apt-get install -y --no-install-recommends nodejs npm >/dev/null 2>&1
        elif command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
            sudo -n apt-get install -y --no-install-recommends nodejs npm >/dev/null 2>&1
        fi
    fi
    if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
        skip_test "node and npm not installed (apt-get install nodejs npm)"
    fi
    if [ ! -d "$dir/node_modules/$module" ]; then
        local log
        if ! log=$(cd "$dir" && npm ci --no-audit --no-fund 2>&1); then
            skip_test "npm ci in $dir failed (no registry access?): $(grep -m1 -E 'FetchError|code|ERR' <<<"$log")"
        fi
    fi
}
