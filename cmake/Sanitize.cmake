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
