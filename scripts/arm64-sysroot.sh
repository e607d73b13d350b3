#!/usr/bin/env bash
# Builds the Debian 12 arm64 sysroot the cross build compiles and links against
# (packaging/toolchain-aarch64.cmake), and that qemu-aarch64-static runs the arm64 programs
# in (-L). Nothing is installed into the host: GDAL's -dev and runtime packages are not
# multiarch, and their arm64 ones would replace the native GDAL.
#   scripts/arm64-sysroot.sh [DIR]      # default build/sysroot-arm64
# mmdebstrap's extract variant only unpacks the packages (no maintainer scripts, no chroot,
# no emulation).
# Environment: MIRROR (default: the host's apt sources).
set -euo pipefail
cd "$(dirname "$0")/.."

sysroot=$(realpath -m "${1:-build/sysroot-arm64}")

# What gimbald's CMakeLists find (find_package / pkg_check_modules), the tests' Catch2, and
# the C and C++ runtime the cross compiler links (libc6-dev, libstdc++-12-dev). Their
# dependencies come with them.
packages=(
  libc6-dev libstdc++-12-dev
  libboost-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libcli11-dev catch2
  libsystemd-dev libgeographiclib-dev libssl-dev libmosquitto-dev
  libgdal-dev libavformat-dev libavcodec-dev libavutil-dev
  libswscale-dev libopencv-dev libopencv-contrib-dev
)
stamp=$sysroot/.gimbald-sysroot
# The tree is rebuilt when this script (its package list, its fix-ups) changes.
want="bookworm arm64 ${packages[*]} $(sha256sum <"$0" | cut -c1-16)"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
  echo "$sysroot"
  exit 0
fi

command -v mmdebstrap >/dev/null || { echo "arm64-sysroot: needs mmdebstrap (scripts/install-deps.sh --cross arm64)" >&2; exit 1; }
rm -rf "$sysroot"
mkdir -p "$(dirname "$sysroot")"
include=$(IFS=,; echo "${packages[*]}")
mirror=()
[ -n "${MIRROR:-}" ] && mirror=("$MIRROR")

# extract hook (runs in the host, $1 is the new tree, the .debs are still in its apt
# cache): dpkg-shlibdeps maps a library to the package that ships it through dpkg's
# database, which an extracted tree has none of. Library files that no installed package
# owns are looked up in DEBIAN/symbols and DEBIAN/shlibs of the tree they were found in,
# so the tree gets every package's symbols and shlibs files there: the .deb's Depends then
# name the arm64 packages with their symbol versions, as a native build's would.
hook='mkdir -p "$1/DEBIAN" && : >"$1/DEBIAN/symbols" && : >"$1/DEBIAN/shlibs"
for deb in "$1"/var/cache/apt/archives/*.deb; do
  ctrl=$(mktemp -d) && dpkg-deb -e "$deb" "$ctrl"
  for f in symbols shlibs; do
    [ -f "$ctrl/$f" ] && cat "$ctrl/$f" >>"$1/DEBIAN/$f"
  done
  rm -rf "$ctrl"
done'

mmdebstrap --variant=extract --architectures=arm64 --include="$include" \
  --extract-hook="$hook" bookworm "$sysroot" "${mirror[@]}" >&2

# Absolute symlinks (libfoo.so -> /lib/aarch64-linux-gnu/libfoo.so.1) would point into the
# host: make them relative within the tree.
while IFS= read -r link; do
  target=$(readlink "$link")
  ln -sfn "$(realpath -m --relative-to="$(dirname "$link")" "$sysroot$target")" "$link"
done < <(find "$sysroot" -type l -lname '/*')

# Links that maintainer scripts make with update-alternatives (not run by extract): GDAL
# pulls in BLAS and LAPACK, whose libblas.so.3 and liblapack.so.3 are such links.
libdir=$sysroot/usr/lib/aarch64-linux-gnu
for alt in blas/libblas.so.3 lapack/liblapack.so.3; do
  if [ -e "$libdir/$alt" ] && [ ! -e "$libdir/${alt#*/}" ]; then
    ln -s "$alt" "$libdir/${alt#*/}"
  fi
done

# qemu-aarch64-static -L looks every path up in the sysroot first: device nodes there
# (mmdebstrap makes /dev when it can) would shadow the host's, and /dev/ptmx outside its
# devpts mount fails with ENODEV (openpty fails; the serial link tests use it).
rm -rf "${sysroot:?}/dev"

echo "$want" >"$stamp"
echo "$sysroot"
