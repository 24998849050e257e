# SPDX-License-Identifier: BSD-3-Clause
# Installing geaware as a CMake package (docs/install.md).
#
# Every library is a component of the package `geaware`, named after its layer (model, traj,
# flatness, control, estimation, io, report, sim, neural, ident, experiments) or its role
# (truth_file, campaign), imported as geaware::<component>. Each component has its own export
# set and targets file; geawareConfig.cmake loads the requested components, the components they
# link and the packages they need, in dependency order, and nothing else: a consumer of
# `COMPONENTS control` gets the controller with Eigen as its only dependency.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(GEAWARE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/geaware)
set(GEAWARE_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/geaware)

# The package a link item comes from, for find_dependency (empty for our own targets).
function(_geaware_package_of item out)
  set(pkg "")
  if(item MATCHES "^Eigen3::")
    set(pkg Eigen3)
  elseif(item STREQUAL "yaml-cpp" OR item MATCHES "^yaml-cpp::")
    set(pkg yaml-cpp)
  elseif(item MATCHES "^nlohmann_json::")
    set(pkg nlohmann_json)
  elseif(item MATCHES "^fmt::")
    set(pkg fmt)
  elseif(item MATCHES "^dlib::")
    set(pkg dlib)
  elseif(item MATCHES "^Ceres::")
    set(pkg Ceres)
  elseif(item MATCHES "^Threads::")
    set(pkg Threads)
  endif()
  set(${out} ${pkg} PARENT_SCOPE)
endfunction()

# geaware_install_component(<component> TARGET <target> [DEPS <component>...] [LINKS <item>...])
# Installs <target> as geaware::<component>. DEPS are the geaware components it links; LINKS its
# other link items (public or private: a static library needs them all at the consumer's link).
function(geaware_install_component component)
  cmake_parse_arguments(ARG "" "TARGET" "DEPS;LINKS" ${ARGN})
  set_target_properties(${ARG_TARGET} PROPERTIES EXPORT_NAME ${component})
  install(TARGETS ${ARG_TARGET} EXPORT geaware_${component}_targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT geaware_${component}_targets NAMESPACE geaware::
          FILE geaware-${component}-targets.cmake DESTINATION ${GEAWARE_INSTALL_CMAKEDIR}
          COMPONENT development)
  set(packages)
  foreach(item IN LISTS ARG_LINKS)
    _geaware_package_of("${item}" pkg)
    if(pkg)
      list(APPEND packages ${pkg})
    endif()
  endforeach()
  list(REMOVE_DUPLICATES packages)
  set_property(GLOBAL APPEND PROPERTY GEAWARE_COMPONENTS ${component})
  set_property(GLOBAL PROPERTY GEAWARE_COMPONENT_DEPS_${component} ${ARG_DEPS})
  set_property(GLOBAL APPEND PROPERTY GEAWARE_COMPONENT_PACKAGES_${component} ${packages})
endfunction()

# Appends link items to an installed component (links added after geaware_layer).
function(geaware_component_links component)
  set(packages)
  foreach(item IN LISTS ARGN)
    _geaware_package_of("${item}" pkg)
    if(pkg)
      list(APPEND packages ${pkg})
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY GEAWARE_COMPONENT_PACKAGES_${component} ${packages})
endfunction()

# Appends geaware components that <component> links (links added after geaware_layer).
function(geaware_component_deps component)
  set_property(GLOBAL APPEND PROPERTY GEAWARE_COMPONENT_DEPS_${component} ${ARGN})
endfunction()

# Writes and installs geawareConfig.cmake and its version file, the headers, the command line's
# data and the notices. Called once, after every library is defined.
function(geaware_install_package)
  get_property(components GLOBAL PROPERTY GEAWARE_COMPONENTS)
  set(table "")
  foreach(c IN LISTS components)
    get_property(deps GLOBAL PROPERTY GEAWARE_COMPONENT_DEPS_${c})
    get_property(pkgs GLOBAL PROPERTY GEAWARE_COMPONENT_PACKAGES_${c})
    if(pkgs)
      list(REMOVE_DUPLICATES pkgs)
    endif()
    string(APPEND table "set(_geaware_deps_${c} \"${deps}\")\n")
    string(APPEND table "set(_geaware_packages_${c} \"${pkgs}\")\n")
  endforeach()
  set(GEAWARE_COMPONENT_LIST "${components}")
  set(GEAWARE_COMPONENT_TABLE "${table}")
  configure_package_config_file(
    ${PROJECT_SOURCE_DIR}/cmake/geawareConfig.cmake.in
    ${PROJECT_BINARY_DIR}/geawareConfig.cmake
    INSTALL_DESTINATION ${GEAWARE_INSTALL_CMAKEDIR})
  # 0.x: a minor version may break the interface, so 0.2 accepts 0.2.y only.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/geawareConfigVersion.cmake
                                   COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/geawareConfig.cmake
                ${PROJECT_BINARY_DIR}/geawareConfigVersion.cmake
          DESTINATION ${GEAWARE_INSTALL_CMAKEDIR} COMPONENT development)
  # The bridge's headers stay out: its library is not exported (it is the command line's
  # `bridge` and `sitl`), and they include the message structs idlc generates in the build tree.
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/geaware
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT development
          PATTERN "bridge" EXCLUDE)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${GEAWARE_INSTALL_DATADIR}/config
          COMPONENT runtime)
  install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/THIRD-PARTY-NOTICES.md
          DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)
endfunction()
