# Cross-compiling gimbald for arm64 (aarch64) on a Debian 12 amd64 machine, with Debian's
# crossbuild-essential-arm64 and the arm64 multiarch libraries (dpkg --add-architecture
# arm64; scripts/install-deps.sh --cross arm64 installs them). Used by
# scripts/package.sh --arch arm64.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# Libraries and their CMake/pkg-config files from /usr/lib/aarch64-linux-gnu only; headers
# and architecture-independent CMake files (/usr/include, /usr/share) are shared.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
set(CMAKE_IGNORE_PATH /usr/lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu/cmake)
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig)
set(ENV{PKG_CONFIG_PATH} "")

# libgeographiclib-dev is not multiarch (arm64's would replace amd64's), so the arm64 build
# links the arm64 runtime library (libgeographiclib23:arm64) with the shared headers.
file(GLOB gimbal_arm64_geographiclib /usr/lib/aarch64-linux-gnu/libGeographicLib.so.*)
if(gimbal_arm64_geographiclib AND NOT EXISTS /usr/lib/aarch64-linux-gnu/libGeographicLib.so)
  list(GET gimbal_arm64_geographiclib 0 gimbal_arm64_geographiclib)
  set(GeographicLib_LIBRARIES ${gimbal_arm64_geographiclib} CACHE FILEPATH "arm64 GeographicLib")
endif()

# Run arm64 programs (man pages from --help, tests) under user-mode QEMU.
find_program(GIMBAL_QEMU_AARCH64 qemu-aarch64-static)
if(GIMBAL_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${GIMBAL_QEMU_AARCH64} -L /usr/aarch64-linux-gnu)
endif()
