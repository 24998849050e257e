# SPDX-License-Identifier: BSD-3-Clause
# cmake -DBUILD_DIR=… -DSOURCE_DIR=… -DWORK_DIR=… -DGENERATOR=… -DCXX_COMPILER=… -DCPACK=…
#       -DVERSION=… -P run_examples.cmake   (tests/install/CMakeLists.txt)
cmake_minimum_required(VERSION 3.22)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${WORK_DIR})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ok")
  set(last_out "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f bin/geaware share/geaware/web/plotly.min.js share/geaware/config/vehicles/paper_quad.yaml
          share/geaware/config/truths/paper_quad_as_built.yaml share/doc/geaware/LICENSE
          share/doc/geaware/copyright include/geaware/control/controller.hpp)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB config ${prefix}/lib*/cmake/geaware/geawareConfig.cmake
                 ${prefix}/lib/*/cmake/geaware/geawareConfig.cmake)
if(NOT config)
  message(FATAL_ERROR "geawareConfig.cmake not installed under ${prefix}/lib…/cmake/geaware")
endif()

set(common -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
           -DCMAKE_PREFIX_PATH=${prefix})

# COMPONENTS control: Eigen and nothing else.
run("configure control only" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/control_only
    -B ${WORK_DIR}/control_only ${common})
# An unknown component is refused with the list of the valid ones.
file(MAKE_DIRECTORY ${WORK_DIR}/bad_component)
file(WRITE ${WORK_DIR}/bad_component/CMakeLists.txt
     "cmake_minimum_required(VERSION 3.22)\nproject(bad LANGUAGES CXX)\n"
     "find_package(geaware 0.2 REQUIRED COMPONENTS controller)\n")
execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/bad_component -B ${WORK_DIR}/bad_build
                        ${common}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT "${out}${err}" MATCHES "no component 'controller'")
  message(FATAL_ERROR "COMPONENTS controller was not refused as unknown:\n${out}\n${err}")
endif()
# A version from another minor series is refused (0.x: SameMinorVersion).
file(WRITE ${WORK_DIR}/bad_component/CMakeLists.txt
     "cmake_minimum_required(VERSION 3.22)\nproject(bad LANGUAGES CXX)\n"
     "find_package(geaware 0.1 REQUIRED COMPONENTS control)\n")
execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/bad_component -B ${WORK_DIR}/bad_build2
                        ${common}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "find_package(geaware 0.1) accepted version ${VERSION}")
endif()

# The two examples, built and run against the install.
foreach(example embed_controller simulate)
  run("configure ${example}" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/${example}
      -B ${WORK_DIR}/${example} ${common})
  run("build ${example}" ${CMAKE_COMMAND} --build ${WORK_DIR}/${example})
endforeach()
run("embed_controller from values" ${WORK_DIR}/embed_controller/embed_controller)
run("embed_controller from the installed vehicle file" ${WORK_DIR}/embed_controller/embed_controller
    ${prefix}/share/geaware/config/vehicles/paper_quad.yaml)
if(NOT last_out MATCHES "throttles 0\\.[0-9]+ 0\\.[0-9]+ 0\\.[0-9]+ 0\\.[0-9]+")
  message(FATAL_ERROR "embed_controller printed no throttles:\n${last_out}")
endif()
run("simulate in the installed as-built truth" ${WORK_DIR}/simulate/simulate
    ${prefix}/share/geaware/config/truths/paper_quad_as_built.yaml)
if(NOT last_out MATCHES "RMSE all [0-9.]+ cm, lowest rotor plane 0\\.[0-9]+ m, no strike")
  message(FATAL_ERROR "simulate did not report a finished flight:\n${last_out}")
endif()

# The installed command line from another directory, its report with the installed plotly.js.
file(MAKE_DIRECTORY ${WORK_DIR}/elsewhere)
execute_process(COMMAND ${prefix}/bin/geaware fly --trajectory lemniscate --height 0.12 --speed 1
                        --controller recommended --report report --quiet
                WORKING_DIRECTORY ${WORK_DIR}/elsewhere RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "installed geaware fly failed (${rc}):\n${out}\n${err}")
endif()
file(GLOB pages ${WORK_DIR}/elsewhere/report/*.html)
if(NOT pages)
  message(FATAL_ERROR "installed geaware fly --report wrote no page:\n${out}\n${err}")
endif()

# The installed command line's shipped suites: `bench --suite beyond`, `robustness` and `faults`
# read the sweep files installed beside it (their grids), not the source tree's; the run's
# provenance names the installed file as its input.
foreach(suite beyond robustness faults)
  set(flags --cases none)
  if(suite STREQUAL "beyond")
    set(flags --cases landing)
  elseif(suite STREQUAL "robustness")
    list(APPEND flags --no-cache)
  endif()
  execute_process(COMMAND ${prefix}/bin/geaware bench --suite ${suite} ${flags} --controllers recommended
                          --seeds 1 --quiet --json -
                  WORKING_DIRECTORY ${WORK_DIR}/elsewhere RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(JSON read ERROR_VARIABLE json_error GET "${out}" provenance inputs 0 path)
  if(NOT rc EQUAL 0 OR NOT read STREQUAL "${prefix}/share/geaware/config/sweeps/${suite}.yaml")
    message(FATAL_ERROR "installed geaware bench --suite ${suite} (${rc}) did not fly the installed sweep file:\n${out}\n${err}")
  endif()
endforeach()

# Built with the Python module (GEAWARE_PYTHON): the installed package imports from another
# directory and loads the installed vehicle file.
if(PYTHON)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/lib/python3/dist-packages
                          ${PYTHON} -c "import geaware; print(geaware.__file__); print(geaware.load_vehicle('${prefix}/share/geaware/config/vehicles/paper_quad.yaml').mass_kg)"
                  WORKING_DIRECTORY ${WORK_DIR}/elsewhere RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "^${prefix}/lib/python3/dist-packages/geaware/__init__.py\n1\.696\n$")
    message(FATAL_ERROR "installed Python module (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "installed Python module: ok")
endif()

# Built with the DDS bridge (GEAWARE_BRIDGE): the installed command line has `bridge` and `sitl`
# (their help states the topics), and no bridge header is installed (the bridge is no component).
if(BRIDGE)
  foreach(sub bridge sitl)
    execute_process(COMMAND ${prefix}/bin/geaware ${sub} --help WORKING_DIRECTORY ${WORK_DIR}/elsewhere
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0 OR NOT out MATCHES "rt/fmu/out/")
      message(FATAL_ERROR "installed geaware ${sub} --help (${rc}) names no PX4 topic:\n${out}\n${err}")
    endif()
  endforeach()
  if(EXISTS ${prefix}/include/geaware/bridge)
    message(FATAL_ERROR "the bridge's headers were installed (they need the build tree's IDL structs)")
  endif()
  message(STATUS "installed geaware bridge/sitl: ok")
endif()

# The Debian package.
run("cpack -G DEB" ${CPACK} -G DEB -B ${WORK_DIR}/deb --config ${BUILD_DIR}/CPackConfig.cmake)
file(GLOB debs ${WORK_DIR}/deb/geaware_${VERSION}_*.deb)
if(NOT debs)
  message(FATAL_ERROR "cpack made no geaware_${VERSION}_*.deb in ${WORK_DIR}/deb")
endif()
list(GET debs 0 deb)
run("dpkg-deb --contents" dpkg-deb --contents ${deb})
foreach(f ./usr/bin/geaware ./usr/share/doc/geaware/copyright ./usr/share/geaware/web/plotly.min.js
          geawareConfig.cmake ./usr/include/geaware/control/controller.hpp)
  string(FIND "${last_out}" "${f}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${deb} lacks ${f}:\n${last_out}")
  endif()
endforeach()
run("dpkg-deb --field" dpkg-deb --field ${deb} Depends)
if(NOT last_out MATCHES "libeigen3-dev")
  message(FATAL_ERROR "${deb} does not depend on libeigen3-dev: ${last_out}")
endif()
# The command line links Cyclone DDS's shared library when built with the bridge: dpkg-shlibdeps
# must have put its package into Depends (where dpkg-shlibdeps exists).
find_program(dpkg_shlibdeps dpkg-shlibdeps)
if(BRIDGE AND dpkg_shlibdeps AND NOT last_out MATCHES "libddsc")
  message(FATAL_ERROR "${deb} built with the bridge does not depend on Cyclone DDS (libddsc…): ${last_out}")
endif()
message(STATUS "installed package: ${deb}")
