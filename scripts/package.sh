#!/usr/bin/env bash
# Builds the Debian packages gimbald_VERSION_ARCH.deb and gimbald-track_VERSION_ARCH.deb
# (contract sections 13 and 20: the tracking process and its OpenCV dependency apart) from this
# checkout: installs what is missing, builds the release binaries with Debian's hardening
# flags in build/package-ARCH, generates the man pages and runs cpack. Prints the paths of
# gimbald-track's .deb, then of gimbald's last (tests/package/check-package.sh takes either
# from beside the other).
#   scripts/package.sh                 # amd64 (the build machine's architecture)
#   scripts/package.sh --arch arm64    # cross-compiled with crossbuild-essential-arm64
#                                      # against build/sysroot-arm64 (scripts/arm64-sysroot.sh)
# Environment: JOBS (parallel build jobs, default nproc).
set -euo pipefail
cd "$(dirname "$0")/.."

arch=$(dpkg --print-architecture)
while [ $# -gt 0 ]; do
  case "$1" in
    --arch) arch=$2; shift 2 ;;
    *) echo "usage: scripts/package.sh [--arch amd64|arm64]" >&2; exit 2 ;;
  esac
done
case "$arch" in amd64|arm64) ;; *) echo "package.sh: unsupported architecture $arch" >&2; exit 2 ;; esac

scripts/install-deps.sh
cross=()
if [ "$arch" != "$(dpkg --print-architecture)" ]; then
  scripts/install-deps.sh --cross "$arch"
  sysroot=$(scripts/arm64-sysroot.sh)
  # GNUInstallDirs picks Debian's multiarch libdir only for native builds; the Wireshark
  # plugin belongs in /usr/lib/aarch64-linux-gnu/wireshark/plugins on arm64 too.
  cross=(-DCMAKE_TOOLCHAIN_FILE="$PWD/packaging/toolchain-aarch64.cmake"
         -DGIMBAL_SYSROOT="$sysroot"
         -DCMAKE_INSTALL_LIBDIR="lib/$(dpkg-architecture -a"$arch" -qDEB_HOST_MULTIARCH 2>/dev/null)")
  export DEB_HOST_ARCH=$arch
fi

# Debian's compiler and linker hardening (what dpkg-buildpackage would set), without -g:
# the package ships stripped binaries and no debug package.
eval "$(DEB_BUILD_MAINT_OPTIONS=hardening=+all DEB_HOST_ARCH=$arch dpkg-buildflags --export=sh)"
export CXXFLAGS="${CXXFLAGS//-g /} $CPPFLAGS"
export LDFLAGS

# Man page dates are the release's (the changelog's), not the build day: reproducible.
SOURCE_DATE_EPOCH=$(dpkg-parsechangelog -l packaging/debian/changelog -STimestamp)
export SOURCE_DATE_EPOCH

build=build/package-$arch
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
# A Release build with GCC: no precompiled headers (cmake/precompiled_headers.cmake says why).
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGIMBAL_WERROR=ON -DGIMBAL_TESTS=OFF \
      -DGIMBAL_BENCH=OFF -DGIMBAL_PACKAGE=ON -DCMAKE_INSTALL_PREFIX=/usr "${cross[@]}" >/dev/null
cmake --build "$build" -j "$jobs"
rm -f "$build"/gimbald_*.deb "$build"/gimbald-track_*.deb
(cd "$build" && cpack -G DEB >/dev/null)
echo "$PWD/$(ls "$build"/gimbald-track_*_"$arch".deb)"
deb=$(ls "$build"/gimbald_*_"$arch".deb)
echo "$PWD/$deb"
