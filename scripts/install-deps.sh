#!/usr/bin/env bash
# Installs the Debian 12 packages gimbald needs to build and test, when any is missing.
# Runs apt-get as root, or through sudo.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libboost-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libcli11-dev catch2
  libsystemd-dev libgeographiclib-dev libssl-dev
  libbenchmark-dev clang libclang-rt-14-dev lld
  socat python3 systemd curl jq
  libmosquitto-dev mosquitto mosquitto-clients python3-paho-mqtt openssl
  dpkg-dev lintian
  tshark prometheus chromium
  libgdal-dev proj-data gdal-bin python3-gdal
  libavformat-dev libavcodec-dev libavutil-dev ffmpeg
  libswscale-dev libopencv-dev libopencv-contrib-dev
  gstreamer1.0-tools gstreamer1.0-plugins-base gstreamer1.0-plugins-good
  gstreamer1.0-plugins-bad gstreamer1.0-plugins-ugly python3-gi gir1.2-gst-rtsp-server-1.0
)

# --cross ARCH (scripts/package.sh --arch arm64): the cross compiler, QEMU and mmdebstrap
# instead. The ARCH libraries are not installed into this machine (GDAL's packages are not
# multiarch): scripts/arm64-sysroot.sh unpacks them into a sysroot under build/.
cross_arch=
if [ "${1:-}" = "--cross" ]; then
  cross_arch=$2
  packages=("crossbuild-essential-$cross_arch" qemu-user-static mmdebstrap)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node.js and npm run the tests' npm packages (node-mavlink). A machine may already have
# them from elsewhere (NodeSource's nodejs bundles npm and conflicts with Debian's npm):
# install Debian's only when the commands are missing.
if [ -z "$cross_arch" ] && { ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; }; then
  missing+=(nodejs npm)
fi
[ ${#missing[@]} -eq 0 ] && exit 0

echo "installing: ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1; then
  SUDO=(sudo)
else
  echo "error: need root or sudo to install: ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -q
"${SUDO[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
