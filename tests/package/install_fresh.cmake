# SPDX-License-Identifier: Apache-2.0
# cmake -DBUILD_DIR=<stepnc build> -DPREFIX=<dir> -P install_fresh.cmake
# Installs the stepnc build into an emptied prefix and checks that the
# package files and a header of every library room are there.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
                OUTPUT_QUIET RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} --prefix ${PREFIX} failed: ${result}")
endif()
foreach(file
    lib/cmake/stepnc/stepncConfig.cmake lib/cmake/stepnc/stepncConfigVersion.cmake
    lib/cmake/stepnc/stepncTargets.cmake lib/cmake/stepnc/StepncGenerate.cmake
    lib/pkgconfig/stepnc.pc bin/expressc bin/stepnc
    include/stepnc/version.h include/stepnc/meta/model.h include/stepnc/exchange/model_file.h
    include/stepnc/machining/generate.h include/stepnc/planning/plan.h include/stepnc/iso14649/machining_schema.h)
  if(NOT EXISTS "${PREFIX}/${file}")
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()
