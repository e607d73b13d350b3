# Cross-compiling gimbald for arm64 (aarch64) on a Debian 12 amd64 machine: Debian's
# crossbuild-essential-arm64 compiles, and every library comes from an arm64 Debian 12
# sysroot (scripts/arm64-sysroot.sh), never from the host: GDAL is not multiarch, so its
# arm64 packages cannot be installed beside the native ones. Used by
# scripts/package.sh --arch arm64 and docs/operations.md "arm64".
#   cmake -B build/arm64 -DCMAKE_TOOLCHAIN_FILE=packaging/toolchain-aarch64.cmake \
#         [-DGIMBAL_SYSROOT=/path/to/sysroot]      # default build/sysroot-arm64
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# The toolchain file is read again for every try_compile: the sysroot travels in the
# environment from the first read to the later ones.
if(NOT GIMBAL_SYSROOT)
  if(DEFINED ENV{GIMBAL_SYSROOT})
    set(GIMBAL_SYSROOT $ENV{GIMBAL_SYSROOT})
  else()
    get_filename_component(GIMBAL_SYSROOT ${CMAKE_CURRENT_LIST_DIR}/../build/sysroot-arm64
                           ABSOLUTE)
  endif()
endif()
if(NOT EXISTS ${GIMBAL_SYSROOT}/usr/lib/aarch64-linux-gnu)
  message(FATAL_ERROR "no arm64 sysroot at ${GIMBAL_SYSROOT}: run scripts/arm64-sysroot.sh")
endif()
set(ENV{GIMBAL_SYSROOT} ${GIMBAL_SYSROOT})
set(GIMBAL_SYSROOT ${GIMBAL_SYSROOT} CACHE PATH "arm64 Debian 12 sysroot (scripts/arm64-sysroot.sh)")

# --sysroot for compiling and linking: headers and libraries from the sysroot. The
# compiler's own runtime (crt files, libgcc, libstdc++'s headers and link-time library)
# comes from the cross toolchain, the same Debian 12 GCC 12.2 and glibc 2.36 as the
# sysroot's libstdc++6 and libc6, which the programs load at run time.
set(CMAKE_SYSROOT ${GIMBAL_SYSROOT})
set(CMAKE_FIND_ROOT_PATH ${GIMBAL_SYSROOT})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# GeographicLib's find module (CMakeLists.txt adds the host's copy of the folder) from the
# sysroot's libgeographiclib-dev first.
list(PREPEND CMAKE_MODULE_PATH ${GIMBAL_SYSROOT}/usr/share/cmake/geographiclib)

# pkg-config reads only the sysroot's .pc files and prefixes their paths with it.
set(ENV{PKG_CONFIG_SYSROOT_DIR} ${GIMBAL_SYSROOT})
set(ENV{PKG_CONFIG_LIBDIR}
    "${GIMBAL_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${GIMBAL_SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_PATH} "")

# Run arm64 programs (man pages from --help, tests) under user-mode QEMU, with the
# sysroot's dynamic loader and libraries.
find_program(GIMBAL_QEMU_AARCH64 qemu-aarch64-static)
if(GIMBAL_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${GIMBAL_QEMU_AARCH64} -L ${GIMBAL_SYSROOT})
endif()
