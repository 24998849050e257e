# SPDX-License-Identifier: BSD-3-Clause
# Runs two commands that each write a file and fails unless the files are the same, line for
# line, apart from comment lines (`#`: the provenance, which names the command line). Arguments
# (-D): FIRST, SECOND: the commands ('|'-separated words); FIRST_FILE, SECOND_FILE: their outputs.
foreach(which FIRST SECOND)
  string(REPLACE "|" ";" cmd "${${which}}")
  execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${which} failed (${rc}): ${err}")
  endif()
  file(STRINGS "${${which}_FILE}" lines)
  list(FILTER lines EXCLUDE REGEX "^#")
  set(${which}_LINES "${lines}")
  list(LENGTH lines n)
  set(${which}_COUNT ${n})
endforeach()
if(FIRST_COUNT EQUAL 0)
  message(FATAL_ERROR "${FIRST_FILE} has no data lines")
endif()
if(NOT FIRST_LINES STREQUAL SECOND_LINES)
  message(FATAL_ERROR "${FIRST_FILE} (${FIRST_COUNT} lines) and ${SECOND_FILE} (${SECOND_COUNT} lines) differ")
endif()
message(STATUS "identical: ${FIRST_COUNT} data lines")
