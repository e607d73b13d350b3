# Precompiled headers for the standard and third-party headers most translation units parse:
# the C++ library, Catch2, Boost.Asio, nlohmann/json, CLI11 (docs/architecture.md "Build
# time"). Only system headers go in, never our own, and a header still has to include what it
# uses (a build without GIMBAL_PCH, as a developer's with ccache, checks that).
#
# ccache caches nothing that uses a precompiled header unless its sloppiness is set for it, so
# with a compiler launcher (ccache, as a developer's build uses) the default is OFF: the cache
# already saves more than the precompiled headers would. An optimized GCC build (the release
# preset, the package) goes without them too: with the standard headers precompiled, GCC 12
# at -O2 inlines `"text" + std::string` where it warns falsely (-Wstringop-overflow, an error
# under GIMBAL_WERROR) in a dozen files. The debug preset and clang's fuzz build use them.
if(CMAKE_CXX_COMPILER_LAUNCHER)
  set(gimbal_pch_default OFF)
elseif(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_BUILD_TYPE AND
       NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(gimbal_pch_default OFF)
else()
  set(gimbal_pch_default ON)
endif()
option(GIMBAL_PCH "Precompile the heavy third-party headers" ${gimbal_pch_default})

# Measured with GCC 12 at -O0 -g (docs/architecture.md "Build time"): a precompiled header
# saves each translation unit the parsing of its headers, but not the templates they make it
# instantiate. Parsing the standard headers below costs 0.5 s, loading them 0.1 s; Catch2
# 1.3 s against 0.2 s; the Asio headers 2.3 s against 0.7 s. nlohmann/json costs 2.4 s parsed
# and 1.2 s precompiled (the parser it instantiates in every unit), CLI11 4.6 s against 3 s:
# those two go only where most translation units include them anyway.
set(GIMBAL_PCH_STD <functional> <map> <optional> <span> <string> <variant> <vector>)
set(GIMBAL_PCH_JSON <nlohmann/json.hpp>)
set(GIMBAL_PCH_ASIO <chrono> <boost/asio/io_context.hpp> <boost/asio/ip/address.hpp>
                    <boost/asio/ip/udp.hpp> <boost/asio/post.hpp> <boost/asio/steady_timer.hpp>)
set(GIMBAL_PCH_CATCH <catch2/catch.hpp>)

# gimbal_pch_donor(<name> <headers>... [LINK <targets>...]): an object library that only
# compiles the precompiled header, for targets with the same flags to share through
# gimbal_reuse_pch.
function(gimbal_pch_donor name)
  cmake_parse_arguments(ARG "" "" "LINK" ${ARGN})
  if(NOT GIMBAL_PCH)
    return()
  endif()
  set(source ${CMAKE_CURRENT_BINARY_DIR}/${name}.cpp)
  file(CONFIGURE OUTPUT ${source} CONTENT "// Compiles ${name}'s precompiled header only.\n")
  add_library(${name} OBJECT ${source})
  target_link_libraries(${name} PRIVATE ${ARG_LINK})
  target_precompile_headers(${name} PRIVATE ${ARG_UNPARSED_ARGUMENTS})
endfunction()

# gimbal_reuse_pch(<target> <donor>): <target> uses <donor>'s precompiled header. Its compile
# flags and definitions must be the donor's (GCC's -Winvalid-pch, an error under -Werror,
# says when they are not).
function(gimbal_reuse_pch target donor)
  if(GIMBAL_PCH)
    target_precompile_headers(${target} REUSE_FROM ${donor})
  endif()
endfunction()

# gimbal_own_pch(<target> <headers>...): <target> compiles a precompiled header of its own;
# only worth it from a few translation units on.
function(gimbal_own_pch target)
  if(NOT GIMBAL_PCH)
    return()
  endif()
  get_target_property(sources ${target} SOURCES)
  list(FILTER sources INCLUDE REGEX "\\.cpp$")
  list(LENGTH sources count)
  if(count GREATER_EQUAL 4)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()
