# SPDX-License-Identifier: Apache-2.0
# cmake -DSOURCE=<consumer> -DBINARY=<dir> -DGENERATOR=<g> -DCOMPILER=<c++>
#       (-DPREFIX=<install prefix> | -DSTEPNC_DIR=<stepnc build dir>)
#       [-DRUN=<program and arguments, ;-list, relative to BINARY>]
#       -P consume.cmake
# Configures, builds and runs a project that finds stepnc with
# find_package(stepnc REQUIRED), in an emptied binary directory.
file(REMOVE_RECURSE "${BINARY}")
set(args -S "${SOURCE}" -B "${BINARY}" -G "${GENERATOR}" "-DCMAKE_CXX_COMPILER=${COMPILER}")
if(PREFIX)
  list(APPEND args "-DCMAKE_PREFIX_PATH=${PREFIX}")
else()
  list(APPEND args "-Dstepnc_DIR=${STEPNC_DIR}")
endif()

function(run step)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${BINARY}" RESULT_VARIABLE result
                  OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message("${output}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${step} failed (${result})")
  endif()
endfunction()

file(MAKE_DIRECTORY "${BINARY}")
run(configure "${CMAKE_COMMAND}" ${args})
run(build "${CMAKE_COMMAND}" --build "${BINARY}")
if(RUN)
  list(POP_FRONT RUN program)
  run(run "${BINARY}/${program}" ${RUN})
endif()
