# SPDX-License-Identifier: BSD-3-Clause
# Script mode (cmake -P): writes build_info.cpp from its template with the current git commit.
# Run at every build by the geaware_build_info target; configure_file rewrites the output only
# when its text changes, so an unchanged commit rebuilds nothing.
#   -DSOURCE_DIR=... -DINPUT=... -DOUTPUT=... -DGEAWARE_VERSION=...
set(GEAWARE_GIT_COMMIT "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE rc ERROR_QUIET)
  if(rc EQUAL 0 AND commit)
    set(GEAWARE_GIT_COMMIT ${commit})
    execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} status --porcelain
                            --untracked-files=no
                    OUTPUT_VARIABLE dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(dirty)
      string(APPEND GEAWARE_GIT_COMMIT "-dirty")
    endif()
  endif()
endif()
configure_file(${INPUT} ${OUTPUT} @ONLY)
