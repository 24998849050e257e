# SPDX-License-Identifier: BSD-3-Clause
# cmake -DSOURCE_DIR=… -P spdx_check.cmake: every source and build file of ours names its licence
# (SPDX-License-Identifier: BSD-3-Clause, LICENSE) in its first three lines.
cmake_minimum_required(VERSION 3.22)
set(missing "")
set(count 0)
foreach(dir include src apps tests examples bench cmake fuzz python)
  file(GLOB_RECURSE files LIST_DIRECTORIES false
       ${SOURCE_DIR}/${dir}/*.cpp ${SOURCE_DIR}/${dir}/*.hpp ${SOURCE_DIR}/${dir}/*.h
       ${SOURCE_DIR}/${dir}/*.c ${SOURCE_DIR}/${dir}/*.cmake ${SOURCE_DIR}/${dir}/*.in
       ${SOURCE_DIR}/${dir}/*.py ${SOURCE_DIR}/${dir}/CMakeLists.txt)
  foreach(f IN LISTS files)
    file(STRINGS ${f} head LIMIT_COUNT 3)
    math(EXPR count "${count} + 1")
    if(NOT head MATCHES "SPDX-License-Identifier: BSD-3-Clause")
      file(RELATIVE_PATH rel ${SOURCE_DIR} ${f})
      list(APPEND missing ${rel})
    endif()
  endforeach()
endforeach()
foreach(f CMakeLists.txt Makefile .ci/run scripts/install-deps scripts/check-docs)
  file(STRINGS ${SOURCE_DIR}/${f} head LIMIT_COUNT 3)
  math(EXPR count "${count} + 1")
  if(NOT head MATCHES "SPDX-License-Identifier: BSD-3-Clause")
    list(APPEND missing ${f})
  endif()
endforeach()
if(missing)
  list(JOIN missing "\n  " text)
  message(FATAL_ERROR "files without 'SPDX-License-Identifier: BSD-3-Clause' in their first "
                      "three lines:\n  ${text}")
endif()
message(STATUS "${count} files carry the SPDX line")
