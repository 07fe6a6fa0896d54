# SPDX-License-Identifier: Apache-2.0
# stepnc_install(): the one way a room puts a target into the installed
# package. The target goes into the export set `stepncTargets`, so it is
# `stepnc::<NAME>` after find_package(stepnc), from an install prefix and
# from a build tree alike (cmake/StepncPackage.cmake writes both).
#
#   stepnc_install(TARGET stepnc_runtime NAME runtime HEADERS include)
#   stepnc_install(TARGET stepnc_iso14649 NAME iso14649
#                  HEADERS a.h b.h INCLUDE_SUBDIR stepnc/iso14649)
#   stepnc_install(TARGET expressc NAME expressc)     # an executable
#
# HEADERS: directories (their *.h files keep their relative paths) or files,
# installed under <includedir>/<INCLUDE_SUBDIR>, which is also the include
# directory consumers get. Libraries are listed, in call order, in the global
# property STEPNC_INSTALLED_LIBRARIES for stepnc.pc.
include(GNUInstallDirs)

function(stepnc_install)
  cmake_parse_arguments(ARG "" "TARGET;NAME;INCLUDE_SUBDIR" "HEADERS" ${ARGN})
  if(NOT ARG_TARGET OR NOT ARG_NAME OR ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "stepnc_install(TARGET <target> NAME <name> [HEADERS ...] [INCLUDE_SUBDIR <dir>])")
  endif()
  set(include_dir "${CMAKE_INSTALL_INCLUDEDIR}")
  if(ARG_INCLUDE_SUBDIR)
    string(APPEND include_dir "/${ARG_INCLUDE_SUBDIR}")
  endif()

  set_target_properties(${ARG_TARGET} PROPERTIES EXPORT_NAME ${ARG_NAME})
  get_target_property(type ${ARG_TARGET} TYPE)
  if(NOT type STREQUAL "EXECUTABLE")
    target_include_directories(${ARG_TARGET} INTERFACE $<INSTALL_INTERFACE:${include_dir}>)
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      set_property(GLOBAL APPEND PROPERTY STEPNC_INSTALLED_LIBRARIES ${ARG_TARGET})
      # Shared libraries: 0.x minors may break the ABI, so the soname has both.
      set_target_properties(${ARG_TARGET} PROPERTIES VERSION "${PROJECT_VERSION}"
        SOVERSION "${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}")
    endif()
  endif()
  install(TARGETS ${ARG_TARGET} EXPORT stepncTargets
    RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}"
    LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}")

  foreach(headers IN LISTS ARG_HEADERS)
    if(NOT IS_ABSOLUTE "${headers}")
      set(headers "${CMAKE_CURRENT_SOURCE_DIR}/${headers}")
    endif()
    if(IS_DIRECTORY "${headers}")
      install(DIRECTORY "${headers}/" DESTINATION "${include_dir}" FILES_MATCHING PATTERN "*.h")
    else()
      install(FILES "${headers}" DESTINATION "${include_dir}")
    endif()
  endforeach()
endfunction()

# Installed tools find the installed shared libraries next to them.
if(BUILD_SHARED_LIBS AND NOT CMAKE_INSTALL_RPATH)
  set(CMAKE_INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
endif()
