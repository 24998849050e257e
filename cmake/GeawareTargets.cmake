# SPDX-License-Identifier: BSD-3-Clause
# Helpers shared by every geaware target.
#
# The wall between layers is enforced by the include path, not by convention: every layer's
# public headers are exposed to the compiler through a per-layer "view" directory holding only
# geaware/<layer>. A target sees the views of the layers it links, and nothing else, so
# `#include <geaware/sim/...>` from a layer that does not link geaware_sim fails to compile.

# Warnings and language level for one of our own targets.
function(geaware_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  # GCC 12 at -O3 reports false -Wrestrict overlaps inside std::string concatenation
  # (GCC bug 105329); the warning carries no information about our code there.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  # No code of ours reads errno after a math call; without this flag every std::sqrt is a call
  # into libm (to set errno on a negative argument) instead of one instruction. It changes no
  # result (unlike -ffast-math).
  target_compile_options(${target} PRIVATE -fno-math-errno)
  if(GEAWARE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# geaware_layer(<layer> SOURCES ... [DEPS ...] [EXTERNAL ...])
# Defines the static library geaware_<layer> (alias geaware::<layer>) from src/<layer>.
function(geaware_layer layer)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;EXTERNAL;PRIVATE_EXTERNAL" ${ARGN})
  set(target geaware_${layer})
  set(view ${PROJECT_BINARY_DIR}/include_views/${layer})
  file(MAKE_DIRECTORY ${view}/geaware)
  if(NOT EXISTS ${view}/geaware/${layer})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/include/geaware/${layer} ${view}/geaware/${layer}
         SYMBOLIC)
  endif()
  add_library(${target} STATIC ${ARG_SOURCES})
  add_library(geaware::${layer} ALIAS ${target})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${view}>
                                              $<INSTALL_INTERFACE:include>)
  set(deps)
  foreach(d IN LISTS ARG_DEPS)
    list(APPEND deps geaware_${d})
  endforeach()
  target_link_libraries(${target} PUBLIC ${deps} ${ARG_EXTERNAL} PRIVATE ${ARG_PRIVATE_EXTERNAL})
  geaware_defaults(${target})
  # A layer compiles its files in batches of six (one translation unit each): the standard,
  # Eigen and fmt headers are parsed once per batch instead of once per file. Helpers private
  # to one file live in its anonymous namespace, so two files of a layer must not define the
  # same name there (shared helpers go to a private header, e.g. src/traj/param_text.hpp).
  set_target_properties(${target} PROPERTIES UNITY_BUILD ${GEAWARE_UNITY_BUILD}
                                             UNITY_BUILD_BATCH_SIZE 6)
  geaware_install_component(${layer} TARGET ${target} DEPS ${ARG_DEPS}
                            LINKS ${ARG_EXTERNAL} ${ARG_PRIVATE_EXTERNAL})
endfunction()

# geaware_test(<name> SOURCES ... LIBS ...): one GoogleTest executable, registered with CTest.
function(geaware_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} geaware_test_support GTest::gtest_main)
  geaware_defaults(${name})
  # GoogleTest and Eigen are parsed once for the whole suite (see tests/CMakeLists.txt).
  if(TARGET geaware_test_pch)
    target_precompile_headers(${name} REUSE_FROM geaware_test_pch)
  endif()
  gtest_discover_tests(${name} TEST_PREFIX "${name}." WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                       PROPERTIES ENVIRONMENT "GEAWARE_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
                       DISCOVERY_TIMEOUT 30)
endfunction()
