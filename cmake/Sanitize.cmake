# SPDX-License-Identifier: BSD-3-Clause
# -DGEAWARE_SANITIZE=address,undefined instruments the whole build (our code and the tests) with
# the named sanitizers. Every finding stops the program (no recovery), so a test under a
# sanitizer fails on its first report. Suppressions, if ever needed, live in
# tests/sanitizer-suppressions with a written reason each.
set(GEAWARE_SANITIZE "" CACHE STRING "Sanitizers for the whole build, e.g. address,undefined")
if(GEAWARE_SANITIZE)
  add_compile_options(-fsanitize=${GEAWARE_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${GEAWARE_SANITIZE})
  message(STATUS "geaware: sanitizers ${GEAWARE_SANITIZE}")
endif()

# -DGEAWARE_FUZZ=ON (clang only; GCC has no libFuzzer) builds the fuzz targets of fuzz/ and
# compiles the whole tree with libFuzzer's coverage instrumentation (-fsanitize=fuzzer-no-link),
# so that the fuzzer sees the branches of the parsers it drives. Use it with
# -DGEAWARE_SANITIZE=address,undefined (the Makefile's clang tree does): a finding is then a
# sanitizer report, not only a crash.
option(GEAWARE_FUZZ "Build the libFuzzer targets of fuzz/ (clang only)" OFF)
if(GEAWARE_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "GEAWARE_FUZZ needs clang (libFuzzer); configure with "
                        "CC=clang-14 CXX=clang++-14 (`make test-fuzz` does)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
  message(STATUS "geaware: fuzz targets, coverage instrumentation")
endif()
