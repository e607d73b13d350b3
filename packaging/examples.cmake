# The example configurations as installed (CMakeLists.txt): config/gimbald.json and
# config/sim.json without their `terrain` section, so that each passes `gimbald
# --check-config` where it is installed (contract section 13; issue 25): the DEMs they name
# (/var/lib/gimbald/dem/*.tif, the build tree's sim-dem.tif) are not there on a fresh machine.
# Everything else, layout included, is the checkout's file. Sets gimbal_examples_dir and
# gimbal_installed_examples.
set(gimbal_examples_dir ${CMAKE_BINARY_DIR}/examples)
set(gimbal_installed_examples)
foreach(example gimbald sim)
  set(source ${CMAKE_CURRENT_SOURCE_DIR}/config/${example}.json)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${source})
  file(READ ${source} text)
  # The section is the file's last member, on one line: `,\n  "terrain": {...}\n}`.
  string(REGEX REPLACE ",\n  \"terrain\": {[^\n]*}\n}\n?$" "\n}\n" installed "${text}")
  string(FIND "${installed}" "\"terrain\"" left)
  if(NOT left EQUAL -1)
    message(FATAL_ERROR "packaging/examples.cmake: config/${example}.json's terrain section "
                        "is no longer its last member on one line; update the pattern")
  endif()
  file(WRITE ${gimbal_examples_dir}/${example}.json.new "${installed}")
  # Rewritten only when it changed: no needless reinstall.
  file(COPY_FILE ${gimbal_examples_dir}/${example}.json.new ${gimbal_examples_dir}/${example}.json
       ONLY_IF_DIFFERENT)
  file(REMOVE ${gimbal_examples_dir}/${example}.json.new)
  list(APPEND gimbal_installed_examples ${gimbal_examples_dir}/${example}.json)
endforeach()
