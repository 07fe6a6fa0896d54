# SPDX-License-Identifier: Apache-2.0
# The package files, written once every room has called stepnc_install():
# stepncConfig.cmake and stepncConfigVersion.cmake (find_package(stepnc)),
# stepncTargets.cmake (the stepnc:: targets), StepncGenerate.cmake
# (stepnc_generate()) and stepnc.pc. The same files serve an install prefix
# (<libdir>/cmake/stepnc) and this build tree (stepnc_DIR=<build dir>).
include(CMakePackageConfigHelpers)

set(STEPNC_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/stepnc")

# 0.x: a minor release may break the API, so only the same minor matches.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/stepncConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMinorVersion)
configure_file("${CMAKE_CURRENT_LIST_DIR}/stepncConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/stepncConfig.cmake" @ONLY)
configure_file("${CMAKE_CURRENT_LIST_DIR}/StepncGenerate.cmake"
  "${PROJECT_BINARY_DIR}/StepncGenerate.cmake" COPYONLY)
export(EXPORT stepncTargets NAMESPACE stepnc:: FILE "${PROJECT_BINARY_DIR}/stepncTargets.cmake")

install(EXPORT stepncTargets NAMESPACE stepnc:: DESTINATION "${STEPNC_CMAKE_DIR}")
install(FILES
  "${PROJECT_BINARY_DIR}/stepncConfig.cmake"
  "${PROJECT_BINARY_DIR}/stepncConfigVersion.cmake"
  "${CMAKE_CURRENT_LIST_DIR}/StepncGenerate.cmake"
  DESTINATION "${STEPNC_CMAKE_DIR}")

# pkg-config: dependents before what they use, as static linking needs.
get_property(libraries GLOBAL PROPERTY STEPNC_INSTALLED_LIBRARIES)
list(REVERSE libraries)
list(TRANSFORM libraries PREPEND "-l")
list(JOIN libraries " " STEPNC_PC_LIBS)
# The prefix is found from the .pc file's place, so a moved prefix works.
file(RELATIVE_PATH STEPNC_PC_TO_PREFIX "/root/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/root")
configure_file("${CMAKE_CURRENT_LIST_DIR}/stepnc.pc.in" "${PROJECT_BINARY_DIR}/stepnc.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/stepnc.pc" DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
