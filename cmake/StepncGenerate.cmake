# SPDX-License-Identifier: Apache-2.0
# stepnc_generate(): compile EXPRESS schemas into a C++ library of typed
# bindings with stepnc::meta reflection, the way protobuf_generate() turns
# .proto files into code.
#
#   stepnc_generate(TARGET my_schemas
#                   SCHEMAS schemas/my_schema.exp ...
#                   [OUT_DIR <dir>]       # default: <binary dir>/<TARGET>
#                   [GROUP_HEADERS <name>_group.h ...])
#   target_link_libraries(my_app PRIVATE my_schemas)
#   // #include "my_schema.h"
#
# Each schema file must declare one schema named like the file
# (`my_schema.exp` holds `SCHEMA my_schema;`): expressc writes
# `<schema>.h` and `<schema>.cc`, so the outputs are known without reading
# the schemas at configure time. All SCHEMAS are compiled together, as one
# closed set (a subtype in one schema is listed in its supertype's table).
# Schemas that use each other also share a header (expressc/README.md,
# "Schemas that use each other"): list it in GROUP_HEADERS so that the
# build knows who writes it.

function(stepnc_generate)
  cmake_parse_arguments(ARG "" "TARGET;OUT_DIR" "SCHEMAS;GROUP_HEADERS" ${ARGN})
  if(NOT ARG_TARGET OR NOT ARG_SCHEMAS)
    message(FATAL_ERROR "stepnc_generate: TARGET and SCHEMAS are required")
  endif()
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "stepnc_generate: unknown arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT ARG_OUT_DIR)
    set(ARG_OUT_DIR "${CMAKE_CURRENT_BINARY_DIR}/${ARG_TARGET}")
  endif()

  # In the stepnc build stepnc::expressc is an alias of the expressc target;
  # after find_package(stepnc) it is the installed (imported) compiler.
  if(NOT TARGET stepnc::expressc)
    message(FATAL_ERROR "stepnc_generate: stepnc::expressc is missing: configure stepnc with "
                        "STEPNC_BUILD_EXPRESSC=ON, or find_package(stepnc) from a prefix that has it")
  endif()
  get_target_property(compiler stepnc::expressc ALIASED_TARGET)
  if(NOT compiler)
    set(compiler "$<TARGET_FILE:stepnc::expressc>")
  endif()

  set(schemas "")
  set(outputs "")
  foreach(schema IN LISTS ARG_SCHEMAS)
    get_filename_component(path "${schema}" ABSOLUTE)
    get_filename_component(stem "${schema}" NAME_WE)
    list(APPEND schemas "${path}")
    list(APPEND outputs "${ARG_OUT_DIR}/${stem}.h" "${ARG_OUT_DIR}/${stem}.cc")
  endforeach()
  foreach(header IN LISTS ARG_GROUP_HEADERS)
    list(APPEND outputs "${ARG_OUT_DIR}/${header}")
  endforeach()

  # expressc rewrites only the files whose text changed; the stamp records
  # the run, and Ninja's restat skips recompiling unchanged outputs.
  set(stamp "${ARG_OUT_DIR}/.${ARG_TARGET}.stamp")
  add_custom_command(
    OUTPUT "${stamp}"
    BYPRODUCTS ${outputs}
    COMMAND "$<TARGET_FILE:stepnc::expressc>" --cpp-out "${ARG_OUT_DIR}" ${schemas}
    COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
    DEPENDS "${compiler}" ${schemas}
    COMMENT "expressc: C++ bindings for ${ARG_TARGET}"
    VERBATIM)

  add_library(${ARG_TARGET} STATIC ${outputs} "${stamp}")
  target_include_directories(${ARG_TARGET} PUBLIC "${ARG_OUT_DIR}")
  target_link_libraries(${ARG_TARGET} PUBLIC stepnc::runtime)
  if(COMMAND stepnc_warnings)
    stepnc_warnings(${ARG_TARGET})
  endif()
endfunction()
