#!/usr/bin/env bash
# Checks the built gimbald and gimbald-track .debs (contract sections 13 and 20): lintian
# reports no error, the control fields and the file lists are what the contract says - gimbald
# free of OpenCV and only recommending gimbald-track, which carries gimbal-track and depends on
# OpenCV's runtime - and the programs run from the packages unpacked into a scratch root
# (dpkg-deb -x; no root, no maintainer scripts).
#   tests/package/check-package.sh build/package-amd64/gimbald_0.1.0_amd64.deb [TRACK_DEB]
# TRACK_DEB defaults to gimbald-track_VERSION_ARCH.deb beside the gimbald one.
set -euo pipefail
deb=$1
[ -f "$deb" ] || { echo "check-package: no such file: $deb" >&2; exit 1; }
failures=0
fail() { echo "check-package: FAIL: $*" >&2; failures=$((failures + 1)); }
pass() { echo "check-package: ok: $*"; }

version=$(sed -n 's/^project(gimbald VERSION \([0-9.]*\).*/\1/p' "$(dirname "$0")/../../CMakeLists.txt")
arch=$(dpkg-deb -f "$deb" Architecture)
track_deb=${2:-$(dirname "$deb")/gimbald-track_${version}_${arch}.deb}

# --- lintian: no errors (warnings and info tags are printed, see docs/operations.md)
lintian_out=$(lintian --tag-display-limit 0 "$deb" 2>&1 | grep -v 'running with root privileges' || true)
[ -n "$lintian_out" ] && echo "$lintian_out"
if grep -q '^E: ' <<<"$lintian_out"; then fail "lintian reports errors"; else pass "lintian: no errors"; fi

# --- control fields
field() { dpkg-deb -f "$deb" "$1"; }
[ "$(field Package)" = gimbald ] && pass "Package: gimbald" || fail "Package is $(field Package)"
[ "$(field Version)" = "$version" ] && pass "Version: $version" || fail "Version $(field Version) != $version"
[ "$(basename "$deb")" = "gimbald_${version}_${arch}.deb" ] && pass "file name" || fail "file name $(basename "$deb")"
for f in Section Priority Maintainer Description Installed-Size; do
  [ -n "$(field "$f")" ] && pass "$f present" || fail "$f missing"
done
depends=$(field Depends)
for lib in libc6 libstdc++6 libsystemd0 libspdlog libfmt libgeographiclib systemd; do
  grep -q "$lib" <<<"$depends" && pass "Depends has $lib" || fail "Depends lacks $lib: $depends"
done
# Visual tracking is apart (contract section 20): no OpenCV here, gimbald-track recommended.
grep -q 'opencv' <<<"$depends" && fail "gimbald Depends on OpenCV: $depends" || pass "Depends has no OpenCV"
[ "$(field Recommends)" = gimbald-track ] && pass "Recommends: gimbald-track" \
  || fail "Recommends is '$(field Recommends)', not gimbald-track"
control=$(mktemp -d)
scratch=$(mktemp -d)
trap 'rm -rf "$control" "$scratch"' EXIT
dpkg-deb -e "$deb" "$control"
[ "$(cat "$control/conffiles")" = /etc/gimbald/gimbald.json ] && pass "conffiles" || fail "conffiles: $(cat "$control/conffiles")"
for script in postinst prerm postrm; do
  [ -x "$control/$script" ] && sh -n "$control/$script" && pass "$script" || fail "$script missing or bad"
done
grep -q 'systemd-sysusers' "$control/postinst" && grep -q 'deb-systemd-helper enable' "$control/postinst" \
  && ! grep -Eq '(systemctl|deb-systemd-invoke) +start' "$control/postinst" \
  && pass "postinst creates the user, enables, does not start" || fail "postinst"

# --- contents
contents=$(dpkg-deb -c "$deb" | awk '{print $1, $6}')
expect() {  # mode-prefix path
  grep -q "^$1[^ ]* \./$2\$" <<<"$contents" && pass "has $2" || fail "lacks $2 ($1)"
}
expect -rwxr-xr-x usr/sbin/gimbald
expect -rwxr-xr-x usr/bin/gimbalctl
expect -rwxr-xr-x usr/bin/gimbal-sim
expect -rw-r--r-- etc/gimbald/gimbald.json
expect -rw-r--r-- lib/systemd/system/gimbald.service
expect -rw-r--r-- usr/lib/sysusers.d/gimbald.conf
expect -rw-r--r-- usr/share/man/man8/gimbald.8.gz
expect -rw-r--r-- usr/share/man/man1/gimbalctl.1.gz
expect -rw-r--r-- usr/share/man/man1/gimbal-sim.1.gz
expect -rw-r--r-- usr/share/man/man5/gimbald.json.5.gz
expect -rw-r--r-- usr/share/doc/gimbald/copyright
# The licence (LICENSE in the source): Apache-2.0, in Debian's machine-readable format.
copyright=$(dpkg-deb --fsys-tarfile "$deb" | tar -xOf - ./usr/share/doc/gimbald/copyright)
grep -qx 'Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/' <<<"$copyright" \
  && grep -qx 'License: Apache-2.0' <<<"$copyright" \
  && grep -q '/usr/share/common-licenses/Apache-2.0' <<<"$copyright" \
  && pass "copyright: machine-readable, Apache-2.0" || fail "copyright is not Apache-2.0 in DEP-5 form"
expect -rw-r--r-- usr/share/doc/gimbald/changelog.gz
expect -rw-r--r-- usr/share/doc/gimbald/configuration.md
expect -rw-r--r-- usr/share/doc/gimbald/examples/gimbald.json
grep -q 'gimbal-track' <<<"$contents" && fail "gimbald holds gimbal-track" || pass "gimbal-track not in gimbald"
# Tools added later (gimbal-replay, gimbal-export) and the dissector come with their sources.
src=$(dirname "$0")/../..
for tool in gimbal-replay gimbal-export; do
  [ -d "$src/tools/$tool" ] && expect -rwxr-xr-x "usr/bin/$tool" \
    && expect -rw-r--r-- "usr/share/man/man1/$tool.1.gz"
done
# The operator console (contract section 11), served from here by default.
[ -f "$src/web/index.html" ] && expect -rw-r--r-- usr/share/gimbald/web/index.html
[ -f "$src/dissectors/gimbald.lua" ] && expect -rw-r--r-- "usr/lib/.*/wireshark/plugins/gimbald.lua"
# A protocol's own dissector, from its home (docs/architecture.md).
for lua in "$src"/lib/protocols/*/dissector/*.lua; do
  [ -f "$lua" ] && expect -rw-r--r-- "usr/lib/.*/wireshark/plugins/$(basename "$lua")"
done

# --- gimbald-track: the tracking process and its OpenCV dependency
if [ -f "$track_deb" ]; then
  tfield() { dpkg-deb -f "$track_deb" "$1"; }
  lintian_out=$(lintian --tag-display-limit 0 "$track_deb" 2>&1 | grep -v 'running with root privileges' || true)
  [ -n "$lintian_out" ] && echo "$lintian_out"
  if grep -q '^E: ' <<<"$lintian_out"; then fail "gimbald-track: lintian reports errors"; else pass "gimbald-track: lintian: no errors"; fi
  [ "$(tfield Package)" = gimbald-track ] && pass "gimbald-track: Package" || fail "gimbald-track: Package is $(tfield Package)"
  [ "$(tfield Version)" = "$version" ] && pass "gimbald-track: Version $version" || fail "gimbald-track: Version $(tfield Version)"
  [ "$(tfield Architecture)" = "$arch" ] && pass "gimbald-track: Architecture" || fail "gimbald-track: Architecture $(tfield Architecture)"
  for f in Section Priority Maintainer Description Installed-Size; do
    [ -n "$(tfield "$f")" ] && pass "gimbald-track: $f present" || fail "gimbald-track: $f missing"
  done
  tdepends=$(tfield Depends)
  # OpenCV's core, image processing and tracking (contrib) modules, libavcodec, libswscale,
  # and the gimbald it speaks to.
  for lib in libopencv-core406 libopencv-imgproc406 libopencv-contrib406 libavcodec59 libswscale6 \
             libc6 libstdc++6 "gimbald (= $version)"; do
    grep -qF "$lib" <<<"$tdepends" && pass "gimbald-track: Depends has $lib" \
      || fail "gimbald-track: Depends lacks $lib: $tdepends"
  done
  # Only the modules it uses: not highgui (GTK/Qt) or videoio directly.
  for lib in libopencv-highgui libopencv-videoio libopencv-dnn; do
    grep -q "$lib" <<<"$tdepends" && fail "gimbald-track: Depends on $lib: $tdepends" \
      || pass "gimbald-track: no direct $lib"
  done
  tcontents=$(dpkg-deb -c "$track_deb" | awk '{print $1, $6}')
  texpect() {
    grep -q "^$1[^ ]* \./$2\$" <<<"$tcontents" && pass "gimbald-track: has $2" || fail "gimbald-track: lacks $2 ($1)"
  }
  texpect -rwxr-xr-x usr/bin/gimbal-track
  texpect -rw-r--r-- usr/share/man/man1/gimbal-track.1.gz
  texpect -rw-r--r-- usr/share/doc/gimbald-track/copyright
  texpect -rw-r--r-- usr/share/doc/gimbald-track/changelog.gz
  # Nothing of gimbald's own: the two packages share no file.
  shared=$(comm -12 <(awk '$1 !~ /^d/ {print $2}' <<<"$contents" | sort) \
                    <(awk '$1 !~ /^d/ {print $2}' <<<"$tcontents" | sort))
  [ -z "$shared" ] && pass "gimbald and gimbald-track share no file" || fail "shared files: $shared"
else
  fail "no gimbald-track package at $track_deb (contract section 20: the tracker is packaged apart)"
fi


# --- run from the unpacked package (only where the package's architecture runs here)
dpkg-deb -x "$deb" "$scratch"
run=()
if [ "$arch" != "$(dpkg --print-architecture)" ]; then
  command -v qemu-aarch64-static >/dev/null || { echo "check-package: no qemu-aarch64-static: not run"; exit $((failures > 0)); }
  # The arm64 libraries the package depends on live in the sysroot it was built against
  # (scripts/arm64-sysroot.sh), not in this machine.
  sysroot=${GIMBAL_SYSROOT:-$src/build/sysroot-arm64}
  [ -d "$sysroot/usr/lib/aarch64-linux-gnu" ] \
    || { echo "check-package: no arm64 sysroot at $sysroot (scripts/arm64-sysroot.sh): not run"; exit $((failures > 0)); }
  run=(qemu-aarch64-static -L "$sysroot")
fi
out=$("${run[@]}" "$scratch/usr/sbin/gimbald" --version)
[ "$out" = "gimbald $version" ] && pass "gimbald --version: $out" || fail "gimbald --version: $out"
if out=$("${run[@]}" "$scratch/usr/sbin/gimbald" --check-config -c "$scratch/etc/gimbald/gimbald.json" 2>&1) \
    && grep -q 'OK, 0 gimbals' <<<"$out"; then
  pass "gimbald --check-config: $out"
else
  fail "gimbald --check-config: $out"
fi
# The examples pass as installed, run from elsewhere than a checkout (issue 25: sim.json named
# build/release/sim-dem.tif, relative to the working directory).
examples=("$scratch"/usr/share/doc/gimbald/examples/*.json)
[ ${#examples[@]} -ge 2 ] && pass "${#examples[@]} examples" || fail "examples: ${examples[*]}"
for example in "${examples[@]}"; do
  if out=$(cd / && "${run[@]}" "$scratch/usr/sbin/gimbald" --check-config -c "$example" 2>&1); then
    pass "examples/$(basename "$example"): $out"
  else
    fail "examples/$(basename "$example") does not pass --check-config as installed: $out"
  fi
done
out=$("${run[@]}" "$scratch/usr/bin/gimbalctl" --help)
grep -q '^SYNOPSIS' <<<"$out" && pass "gimbalctl --help" || fail "gimbalctl --help"
out=$("${run[@]}" "$scratch/usr/bin/gimbal-sim" --version)
[ "$out" = "gimbal-sim $version" ] && pass "gimbal-sim --version: $out" || fail "gimbal-sim --version: $out"
# gimbal-track from its own unpacked package.
if [ -f "$track_deb" ]; then
  tscratch=$(mktemp -d)
  trap 'rm -rf "$control" "$scratch" "$tscratch"' EXIT
  dpkg-deb -x "$track_deb" "$tscratch"
  out=$("${run[@]}" "$tscratch/usr/bin/gimbal-track" --version 2>&1 || true)
  [ "$out" = "gimbal-track $version" ] && pass "gimbal-track --version: $out" || fail "gimbal-track --version: $out"
  out=$("${run[@]}" "$tscratch/usr/bin/gimbal-track" --help 2>&1 || true)
  grep -q '^SYNOPSIS' <<<"$out" && pass "gimbal-track --help" || fail "gimbal-track --help"
  page=$tscratch/usr/share/man/man1/gimbal-track.1.gz
  warnings=$(LC_ALL=C.UTF-8 MANWIDTH=80 man --warnings -l "$page" 2>&1 >/dev/null || true)
  [ -z "$warnings" ] && grep -q "^\.TH .*gimbal.* $version\"" <<<"$(zcat "$page")" \
    && pass "gimbald-track: man page gimbal-track.1.gz" || fail "gimbald-track: man page: $warnings"
  # Both packages installed together: the packaged /usr/sbin/gimbald finds /usr/bin/gimbal-track
  # by itself (docs/tracking.md "gimbald's side") and it says hello.
  if [ ${#run[@]} -eq 0 ]; then
    both=$(mktemp -d)
    trap 'rm -rf "$control" "$scratch" "$tscratch" "$both"' EXIT
    dpkg-deb -x "$deb" "$both"
    dpkg-deb -x "$track_deb" "$both"
    port=$(shuf -i 20000-40000 -n 1)
    printf '{"command": {"port": %d}, "gimbals": [{"name": "sim", "protocol": "orion",
      "link": {"type": "sim"}, "video": {"input": "udp://127.0.0.1:%d", "tracking": {}}}]}\n' \
      "$port" "$((port + 1))" >"$both/tracking.json"
    (cd / && exec env -u GIMBAL_TRACK "$both/usr/sbin/gimbald" -c "$both/tracking.json" \
      >"$both/gimbald.log" 2>&1) &
    daemon=$!
    for _ in $(seq 50); do
      grep -q '"event":"track_process_ready"' "$both/gimbald.log" && break
      sleep 0.2
    done
    kill "$daemon" 2>/dev/null || true
    wait "$daemon" 2>/dev/null || true
    if grep -q '"event":"track_process_ready"' "$both/gimbald.log" \
        && grep -q "\"program\":\"$both/usr/bin/gimbal-track\"" "$both/gimbald.log"; then
      pass "packaged gimbald starts the packaged gimbal-track"
    else
      fail "packaged gimbald and gimbal-track: $(grep -E 'track_process|error' "$both/gimbald.log" | head -5)"
    fi
  fi
fi
# Man pages render without groff warnings and carry the version. (Here-strings,
# not pipes into grep -q: with pipefail an early grep exit SIGPIPEs the writer.)
for page in "$scratch"/usr/share/man/man*/*.gz; do
  warnings=$(LC_ALL=C.UTF-8 MANWIDTH=80 man --warnings -l "$page" 2>&1 >/dev/null || true)
  [ -z "$warnings" ] && grep -q "^\.TH .*gimbal.* $version\"" <<<"$(zcat "$page")" \
    && pass "man page $(basename "$page")" || fail "man page $(basename "$page"): $warnings"
  # No Markdown shows through (issue 25: backticks and links on the pages): `code`,
  # [text](link), **bold**, <!-- markers -->.
  raw=$(LC_ALL=C.UTF-8 MANWIDTH=80 man -l "$page" 2>/dev/null | grep -nE '`|\]\(|\*\*[A-Za-z]|<!--' || true)
  [ -z "$raw" ] && pass "man page $(basename "$page"): no raw Markdown" \
    || fail "man page $(basename "$page") shows raw Markdown: $raw"
done
# gimbald(8) points at every program of the package.
see_also=$(LC_ALL=C.UTF-8 MANWIDTH=200 man -l "$scratch/usr/share/man/man8/gimbald.8.gz" 2>/dev/null \
  | sed -n '/^SEE ALSO/,/^[A-Z]/p')
for tool in gimbalctl gimbal-sim gimbal-replay gimbal-export gimbald.json; do
  [ -f "$scratch/usr/share/man/man1/$tool.1.gz" ] || [ -f "$scratch/usr/share/man/man5/$tool.5.gz" ] || continue
  grep -q "$tool(" <<<"$see_also" && pass "gimbald(8) SEE ALSO $tool" || fail "gimbald(8) SEE ALSO lacks $tool: $see_also"
done

if [ $failures -gt 0 ]; then
  echo "check-package: $failures failure(s)" >&2
  exit 1
fi
echo "check-package: all checks passed for $(basename "$deb") and $(basename "$track_deb")"
