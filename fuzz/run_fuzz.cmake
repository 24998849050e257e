# SPDX-License-Identifier: BSD-3-Clause
# cmake -DFUZZER=… -DCORPUS=… -DWORK=… -DDICT=… [-DRUNS=N] [-DSECONDS=S] [-DSEED=N] [-DFRESH=ON]
#       -P run_fuzz.cmake
# Runs one libFuzzer target over its seed corpus (fuzz/corpus/<target>/, read only: new inputs go
# to WORK/corpus, which FRESH empties first) for RUNS executions or SECONDS seconds, whichever
# ends first. A crash, a sanitizer report, a leak, an input slower than 10 s or over 2 GB fails
# the run; the input is written to WORK/artifacts/ (add it to the seed corpus once fixed).
cmake_minimum_required(VERSION 3.22)
foreach(var FUZZER CORPUS WORK DICT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_fuzz.cmake: -D${var}=… is required")
  endif()
endforeach()
if(FRESH)
  file(REMOVE_RECURSE ${WORK}/corpus)
endif()
file(MAKE_DIRECTORY ${WORK}/corpus ${WORK}/artifacts)
set(args -dict=${DICT} -artifact_prefix=${WORK}/artifacts/ -timeout=10 -rss_limit_mb=2048
         -print_final_stats=1)
if(DEFINED RUNS)
  list(APPEND args -runs=${RUNS})
endif()
if(DEFINED SECONDS)
  list(APPEND args -max_total_time=${SECONDS})
endif()
if(DEFINED SEED)
  list(APPEND args -seed=${SEED})
endif()
message(STATUS "${FUZZER} ${args} ${WORK}/corpus ${CORPUS}")
execute_process(COMMAND ${FUZZER} ${args} ${WORK}/corpus ${CORPUS} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${FUZZER}: exit ${rc}; the input is in ${WORK}/artifacts/")
endif()
