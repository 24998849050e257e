# SPDX-License-Identifier: BSD-3-Clause
# `cpack -G DEB` in the build tree makes a Debian package of the install (docs/install.md): the
# command line, the static libraries with their headers and CMake package, the vehicle and truth
# files, plotly.js for the reports, the licence and the notices.
install(FILES ${PROJECT_SOURCE_DIR}/cmake/debian-copyright DESTINATION ${CMAKE_INSTALL_DOCDIR}
        RENAME copyright COMPONENT runtime)

set(CPACK_PACKAGE_NAME geaware)
set(CPACK_PACKAGE_VENDOR "the geaware authors")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "the geaware authors <geaware@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# The shared libraries the command line links (yaml-cpp, fmt, Ceres, dlib, …) from
# dpkg-shlibdeps; Eigen for the headers every component includes; the other development
# packages a consumer's find_package needs for the components that use them.
find_program(GEAWARE_DPKG_SHLIBDEPS dpkg-shlibdeps)
if(GEAWARE_DPKG_SHLIBDEPS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libeigen3-dev (>= 3.4)")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "libyaml-cpp-dev, nlohmann-json3-dev, libfmt-dev, libceres-dev, libdlib-dev, libmatio-dev, chromium")
# The Python module (python/, GEAWARE_PYTHON) is built for one Python version and imports numpy.
if(GEAWARE_PYTHON)
  math(EXPR geaware_python_next "${Python3_VERSION_MINOR} + 1")
  string(APPEND CPACK_DEBIAN_PACKAGE_RECOMMENDS
         ", python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), "
         "python3 (<< ${Python3_VERSION_MAJOR}.${geaware_python_next}), python3-numpy, "
         # python3 -m geaware.sweep on a Dask cluster (docs/sweeps.md); --processes needs none.
         "python3-distributed")
endif()
include(CPack)
