# SPDX-License-Identifier: BSD-3-Clause
# Runs one command and checks its exit code and output; used by the CLI tests (CMakeLists.txt).
#
#   cmake -DEXPECT_EXIT=<code> [checks...] -P run_expect.cmake -- <program> [args...]
#
# Checks (each optional; the *_LINE_REGEX and *_CONTAINS ones take a list, every item must hold):
#   STDOUT_FIRST_LINE   the first line of stdout, exactly
#   STDOUT_LINE_REGEX   regexes, each matching at least one whole line of stdout
#   STDERR_LINE_REGEX   the same for stderr
#   STDOUT_CONTAINS     literal substrings of stdout
#   STDERR_CONTAINS     literal substrings of stderr
#   STDOUT_JSON         PATH=VALUE items: stdout parsed as JSON (CMake's string(JSON)), the
#                       member or element at PATH ('/'-separated keys and array indices) equals
#                       VALUE: the same text, or the same number (0.3 matches 0.29999999999999999)
# Every failed check is reported (with both outputs) before the script fails, so one run says
# everything that is wrong.

if(NOT DEFINED EXPECT_EXIT)
  message(FATAL_ERROR "run_expect.cmake: EXPECT_EXIT is required")
endif()

# The command is everything after "--".
set(command)
set(after_separator FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE ${last})
  if(after_separator)
    list(APPEND command "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")
    set(after_separator TRUE)
  endif()
endforeach()
if(NOT command)
  message(FATAL_ERROR "run_expect.cmake: no command after '--'")
endif()

execute_process(COMMAND ${command}
                RESULT_VARIABLE exit_code
                OUTPUT_VARIABLE out
                ERROR_VARIABLE err)

set(failures)
if(NOT exit_code STREQUAL EXPECT_EXIT)
  list(APPEND failures "exit code ${exit_code}, expected ${EXPECT_EXIT}")
endif()

# CMake stops splitting a list at an unbalanced '[', which regexes and program output may hold:
# lists are split with square brackets hidden behind placeholders, restored item by item.
function(protect text out_var)
  string(REPLACE "[" "<geaware-lsb>" text "${text}")
  string(REPLACE "]" "<geaware-rsb>" text "${text}")
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()
function(unprotect text out_var)
  string(REPLACE "<geaware-lsb>" "[" text "${text}")
  string(REPLACE "<geaware-rsb>" "]" text "${text}")
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

# Each regex must match at least one line of `text`.
function(check_line_regexes stream text regexes)
  protect("${text}" text)
  string(REPLACE ";" "<geaware-semicolon>" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  protect("${regexes}" regexes)
  foreach(protected_regex IN LISTS regexes)
    unprotect("${protected_regex}" regex)
    set(found FALSE)
    foreach(protected_line IN LISTS lines)
      unprotect("${protected_line}" line)
      string(REPLACE "<geaware-semicolon>" ";" line "${line}")
      if(line MATCHES "${regex}")
        set(found TRUE)
        break()
      endif()
    endforeach()
    if(NOT found)
      list(APPEND failures "no line of ${stream} matches '${regex}'")
    endif()
  endforeach()
  set(failures "${failures}" PARENT_SCOPE)
endfunction()

# Each needle must occur in `text`.
function(check_contains stream text needles)
  protect("${needles}" needles)
  foreach(protected_needle IN LISTS needles)
    unprotect("${protected_needle}" needle)
    string(FIND "${text}" "${needle}" pos)
    if(pos EQUAL -1)
      list(APPEND failures "${stream} does not contain '${needle}'")
    endif()
  endforeach()
  set(failures "${failures}" PARENT_SCOPE)
endfunction()

if(DEFINED STDOUT_FIRST_LINE)
  string(FIND "${out}" "\n" newline)
  string(SUBSTRING "${out}" 0 ${newline} first_line)
  if(NOT first_line STREQUAL STDOUT_FIRST_LINE)
    list(APPEND failures "first line of stdout is '${first_line}', expected '${STDOUT_FIRST_LINE}'")
  endif()
endif()
check_line_regexes(stdout "${out}" "${STDOUT_LINE_REGEX}")
check_line_regexes(stderr "${err}" "${STDERR_LINE_REGEX}")
check_contains(stdout "${out}" "${STDOUT_CONTAINS}")
check_contains(stderr "${err}" "${STDERR_CONTAINS}")

# Each PATH=VALUE of `queries` holds in the JSON document `text`.
function(check_json stream text queries)
  foreach(query IN LISTS queries)
    string(FIND "${query}" "=" eq)
    if(eq EQUAL -1)
      message(FATAL_ERROR "run_expect.cmake: STDOUT_JSON item '${query}' is not PATH=VALUE")
    endif()
    string(SUBSTRING "${query}" 0 ${eq} path)
    math(EXPR from "${eq} + 1")
    string(SUBSTRING "${query}" ${from} -1 expected)
    string(REPLACE "/" ";" keys "${path}")
    string(JSON got ERROR_VARIABLE error GET "${text}" ${keys})
    if(error)
      list(APPEND failures "${stream} as JSON has no ${path}: ${error}")
    elseif(NOT (got STREQUAL expected OR got EQUAL expected))
      list(APPEND failures "${stream} as JSON has ${path} = '${got}', expected '${expected}'")
    endif()
  endforeach()
  set(failures "${failures}" PARENT_SCOPE)
endfunction()
check_json(stdout "${out}" "${STDOUT_JSON}")

if(failures)
  list(JOIN failures "\n  " report)
  list(JOIN command " " shown)
  message(FATAL_ERROR "${shown}\n  ${report}\n--- stdout ---\n${out}--- stderr ---\n${err}")
endif()
