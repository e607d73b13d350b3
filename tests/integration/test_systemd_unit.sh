#!/usr/bin/env bash
# systemd/gimbald.service: `systemd-analyze verify` accepts it without a single warning, it
# carries the directives the interface contract and docs/operations.md rely on, has no
# ExecStartPre (RestartPreventExitStatus=1 does not cover one: a configuration error there
# would restart every 2 s), and gimbald --check-config passes on the shipped configuration.
# Exit 77 (skipped) when systemd-analyze is not installed.
set -uo pipefail

src=${GIMBAL_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
unit=$src/systemd/gimbald.service
failures=0
fail() {
    echo "FAIL: $*" >&2
    failures=$((failures + 1))
}

# shellcheck source=skip.sh
. "$(dirname "$0")/skip.sh"
if ! command -v systemd-analyze >/dev/null 2>&1; then
    skip_test "systemd-analyze is not installed"
fi

# verify checks that ExecStart binaries exist: point a copy of the unit at the built binary
# (or at a stand-in before gimbald is built) and at the source tree's configuration.
binary=${GIMBALD:-}
if [[ -n $binary && ! -x $binary ]]; then
    skip_test "$binary is not built"
fi
if [[ -z $binary ]]; then
    binary=$(type -P true)
    echo "note: there is no gimbald target; $binary stands in for it in ExecStart"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed -e "s|/usr/sbin/gimbald|$binary|g" \
    -e "s|/etc/gimbald/gimbald.json|$src/config/gimbald.json|g" \
    "$unit" >"$tmp/gimbald.service"

# verify exits 0 even for unknown keys or invalid values (it only warns): any message about
# our unit is a failure. Messages about other units on this machine are not ours to judge.
output=$(systemd-analyze verify "$tmp/gimbald.service" 2>&1)
status=$?
ours=$(grep -F "gimbald.service" <<<"$output" || true)
if [[ $status -ne 0 || -n $ours ]]; then
    fail "systemd-analyze verify (exit $status):"
    echo "$output" >&2
fi

# A deliberately broken copy must be caught, or the check above proves nothing.
sed -e 's|^WatchdogSec=10$|WatchdogSec=10\nWatchdogSecs=10|' "$tmp/gimbald.service" >"$tmp/broken.service"
broken_output=$(systemd-analyze verify "$tmp/broken.service" 2>&1)
if ! grep -q "WatchdogSecs" <<<"$broken_output"; then
    fail "systemd-analyze verify did not report an unknown key; the check is blind"
fi

# The directives other parts of the product depend on, exactly.
required=(
    "Type=notify"
    "ExecStart=/usr/sbin/gimbald -c /etc/gimbald/gimbald.json"
    'ExecReload=/bin/kill -HUP $MAINPID'
    "WatchdogSec=10"
    "Restart=on-failure"
    "RestartSec=2"
    "RestartPreventExitStatus=1"
    "User=gimbald"
    "Group=gimbald"
    "SupplementaryGroups=dialout"
    "LogsDirectory=gimbald"
    "NoNewPrivileges=yes"
    "ProtectSystem=strict"
    "ProtectHome=yes"
    "PrivateTmp=yes"
    "PrivateDevices=no"
    "DevicePolicy=closed"
    "DeviceAllow=char-ttyUSB rw"
    "DeviceAllow=char-ttyACM rw"
    "DeviceAllow=char-ttyS rw"
    "RestrictAddressFamilies=AF_INET AF_INET6 AF_UNIX"
    "ProtectKernelTunables=yes"
    "ProtectKernelModules=yes"
    "ProtectControlGroups=yes"
    "RestrictNamespaces=yes"
    "LockPersonality=yes"
    "MemoryDenyWriteExecute=yes"
    "RestrictRealtime=yes"
    "SystemCallArchitectures=native"
)
for directive in "${required[@]}"; do
    grep -qxF "$directive" "$unit" || fail "missing directive: $directive"
done
# systemd applies RestartPreventExitStatus= to the main process only: an ExecStartPre that
# exits 1 is restarted like any failure (issue 25). gimbald checks its configuration itself.
if grep -q '^ExecStartPre=' "$unit"; then
    fail "ExecStartPre: its exit 1 would be restarted every RestartSec"
fi

# Exposure score, for information (systemd >= 250 can rate a unit file offline).
if security=$(systemd-analyze security --offline=true "$tmp/gimbald.service" 2>/dev/null); then
    grep -F "Overall exposure level" <<<"$security" || true
fi

# The configuration check the daemon makes at start, when it is built: the shipped
# configuration passes, a broken one fails with exit code 1 (the status the unit does not
# restart on), at start as well as with --check-config.
if [[ -n ${GIMBALD:-} ]]; then
    # Its terrain section names /var/lib/gimbald/dem/*.tif: a DEM written by gimbal-sim
    # stands in for it, as --check-config opens every terrain file.
    example="$src/config/gimbald.json"
    if [[ -n ${GIMBAL_SIM:-} ]] && "$GIMBAL_SIM" --write-dem "$tmp/dem.tif" >/dev/null; then
        sed -e "s|/var/lib/gimbald/dem/\*.tif|$tmp/dem.tif|" "$example" >"$tmp/example.json"
        example="$tmp/example.json"
    fi
    if ! "$GIMBALD" --check-config -c "$example" >/dev/null; then
        fail "gimbald --check-config rejects config/gimbald.json"
    fi
    echo '{"gimbals": [], "laser": {"allow_fire": "yes"}}' >"$tmp/bad.json"
    "$GIMBALD" --check-config -c "$tmp/bad.json" >/dev/null 2>&1
    status=$?
    [[ $status -eq 1 ]] || fail "gimbald --check-config on a broken file exited $status, not 1"
    timeout 20 "$GIMBALD" -c "$tmp/bad.json" >/dev/null 2>&1 </dev/null
    status=$?
    [[ $status -eq 1 ]] || fail "gimbald on a broken file exited $status at start, not 1"
fi

if [[ $failures -ne 0 ]]; then
    echo "$failures failure(s)" >&2
    exit 1
fi
echo "OK: systemd/gimbald.service"
