# The Debian packages (scripts/package.sh; contract sections 13 and 20): man pages generated
# from the built programs and docs/configuration.md, the Debian doc files, and the CPack DEB
# settings. Included by the top CMakeLists.txt when GIMBAL_PACKAGE is ON (with
# CMAKE_INSTALL_PREFIX /usr). Every executable installed by an install() rule is packaged;
# tools listed below also get a man page. Two packages from one build (CPack components):
# gimbald (component gimbald: everything but) and gimbald-track (component track: gimbal-track,
# which links OpenCV). gimbald only Recommends gimbald-track: OpenCV's runtime pulls about 147
# packages (Qt5, HDF5, tesseract) that a gimbald without visual tracking does not need.

find_package(Python3 REQUIRED COMPONENTS Interpreter)
set(gimbal_packaging ${CMAKE_CURRENT_SOURCE_DIR}/packaging)
set(gimbal_man_dir ${CMAKE_BINARY_DIR}/man)
file(MAKE_DIRECTORY ${gimbal_man_dir})

# Cross builds run the target's programs for their --help through the emulator
# (packaging/toolchain-aarch64.cmake sets qemu-aarch64-static).
set(gimbal_run_wrapper "")
if(CMAKE_CROSSCOMPILING_EMULATOR)
  list(JOIN CMAKE_CROSSCOMPILING_EMULATOR " " gimbal_run_wrapper)
endif()

# --- man pages: <tool>(1) or gimbald(8) from --help/--version, gimbald.json(5) from the docs
set(gimbal_man_pages)
foreach(program IN ITEMS gimbald gimbalctl gimbal-sim gimbal-replay gimbal-export gimbal-track)
  if(NOT TARGET ${program})
    continue()
  endif()
  set(section 1)
  if(program STREQUAL "gimbald")
    set(section 8)
  endif()
  set(component gimbald)
  if(program STREQUAL "gimbal-track")
    set(component track)
  endif()
  set(page ${gimbal_man_dir}/${program}.${section}.gz)
  add_custom_command(
    OUTPUT ${page}
    COMMAND ${Python3_EXECUTABLE} ${gimbal_packaging}/man/help2roff.py --section ${section}
            --wrapper "${gimbal_run_wrapper}" --output ${page} $<TARGET_FILE:${program}>
    DEPENDS ${program} ${gimbal_packaging}/man/help2roff.py ${gimbal_packaging}/man/md2roff.py
    COMMENT "Man page ${program}(${section}) from ${program} --help"
    VERBATIM)
  list(APPEND gimbal_man_pages ${page})
  install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man${section} COMPONENT ${component})
endforeach()

set(config_page ${gimbal_man_dir}/gimbald.json.5.gz)
add_custom_command(
  OUTPUT ${config_page}
  COMMAND ${Python3_EXECUTABLE} ${gimbal_packaging}/man/md2roff.py --version ${PROJECT_VERSION}
          --output ${config_page} ${CMAKE_CURRENT_SOURCE_DIR}/docs/configuration.md
  DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/docs/configuration.md ${gimbal_packaging}/man/md2roff.py
  COMMENT "Man page gimbald.json(5) from docs/configuration.md"
  VERBATIM)
install(FILES ${config_page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man5)

# --- /usr/share/doc/gimbald: copyright, changelog.gz (a native package's Debian changelog).
# The changelog's newest entry must name the project version: one source of truth.
file(STRINGS ${gimbal_packaging}/debian/changelog changelog_head LIMIT_COUNT 1)
if(NOT changelog_head MATCHES "^gimbald \\(${PROJECT_VERSION}\\) ")
  message(FATAL_ERROR "packaging/debian/changelog: the first entry is \"${changelog_head}\"; "
                      "add an entry for version ${PROJECT_VERSION} (project() in CMakeLists.txt)")
endif()
set(changelog_gz ${CMAKE_BINARY_DIR}/changelog.gz)
add_custom_command(
  OUTPUT ${changelog_gz}
  COMMAND ${Python3_EXECUTABLE} ${gimbal_packaging}/man/gzipn.py
          ${gimbal_packaging}/debian/changelog ${changelog_gz}
  DEPENDS ${gimbal_packaging}/debian/changelog
  VERBATIM)
add_custom_target(package_docs ALL DEPENDS ${gimbal_man_pages} ${config_page} ${changelog_gz})
install(FILES ${changelog_gz} ${gimbal_packaging}/debian/copyright DESTINATION ${CMAKE_INSTALL_DOCDIR})
if(TARGET gimbal-track)
  install(FILES ${changelog_gz} ${gimbal_packaging}/debian/copyright
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/gimbald-track COMPONENT track)
endif()

# --- CPack: gimbald_VERSION_ARCH.deb
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME gimbald)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "gimbald maintainers <maintainers@users.noreply.h-seed-69d788ad.example>")
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_STRIP_FILES TRUE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION net)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(GIMBAL_HOMEPAGE "" CACHE STRING "Homepage field of the .deb (left out when empty)")
if(GIMBAL_HOMEPAGE)
  set(CPACK_DEBIAN_PACKAGE_HOMEPAGE ${GIMBAL_HOMEPAGE})
endif()
set(CPACK_DEBIAN_GIMBALD_DESCRIPTION
    "ground-control daemon for camera gimbals (Trillium Orion, Viewpro)
gimbald holds serial and TCP links to Trillium Orion gimbals (OrionPublic
protocol) and Viewpro gimbals (target-GPS protocol), keeps a live state model
from their telemetry and serves a JSON-over-UDP command socket for geopoint,
path, laser and camera control. It reads the aircraft's state as MAVLink and
forwards it to every gimbal. It runs as a hardened systemd service with
JSON-lines logs.

The package also holds gimbalctl, the command-line client, gimbal-sim,
simulated gimbals for tests, demos and operator training, and gimbal-replay
and gimbal-export, which play a flight recording back through gimbald or
export its tracks and camera footprints as GeoJSON, KML or CSV. The service is
enabled but not started: list the gimbals in /etc/gimbald/gimbald.json first.")
# Dependencies from the binaries (dpkg-shlibdeps), plus systemd for the unit and the
# sysusers file the postinst applies.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_GIMBALD_PACKAGE_DEPENDS "systemd")
set(CPACK_DEBIAN_GIMBALD_PACKAGE_CONTROL_EXTRA
    ${gimbal_packaging}/debian/conffiles ${gimbal_packaging}/debian/postinst
    ${gimbal_packaging}/debian/prerm ${gimbal_packaging}/debian/postrm)

# The split (contract section 20): one .deb per component, both built from source gimbald.
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL gimbald)
set(CPACK_DEBIAN_PACKAGE_SOURCE gimbald)
set(CPACK_DEBIAN_GIMBALD_PACKAGE_NAME gimbald)
if(TARGET gimbal-track)
  list(APPEND CPACK_COMPONENTS_ALL track)
  set(CPACK_DEBIAN_TRACK_PACKAGE_NAME gimbald-track)
  set(CPACK_DEBIAN_GIMBALD_PACKAGE_RECOMMENDS "gimbald-track")
  # The wire protocol between the two is versioned, and only this build's pair is tested.
  set(CPACK_DEBIAN_TRACK_PACKAGE_DEPENDS "gimbald (= ${PROJECT_VERSION})")
  set(CPACK_DEBIAN_TRACK_DESCRIPTION
      "visual tracking for gimbald (OpenCV)
gimbal-track is the process gimbald starts for a gimbal whose video has
\"tracking\" configured: it decodes the gimbal's video while a track runs,
follows the object the operator picked in the picture with OpenCV's CSRT or
KCF tracker, a confidence of its own and a re-detection search, and reports
its box for every frame to gimbald, which keeps the camera on it and locates
it on the ground. It is a separate package because OpenCV's runtime is large;
gimbald works without it, visual tracking then answers \"unavailable\".")
endif()
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
set(CPACK_DEBIAN_COMPRESSION_TYPE xz)
if(CMAKE_CROSSCOMPILING AND CMAKE_SYSTEM_PROCESSOR STREQUAL "aarch64")
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
endif()
# A cross build's libraries are in its sysroot (packaging/toolchain-aarch64.cmake):
# dpkg-shlibdeps looks there first, and finds their packages' symbols and shlibs files in
# the sysroot's DEBIAN folder (scripts/arm64-sysroot.sh).
if(CMAKE_CROSSCOMPILING AND CMAKE_SYSROOT)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS
      ${CMAKE_SYSROOT}/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}
      ${CMAKE_SYSROOT}/lib/${CMAKE_LIBRARY_ARCHITECTURE})
endif()
set(CPACK_INSTALL_DEFAULT_DIRECTORY_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ
                                                GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
include(CPack)
