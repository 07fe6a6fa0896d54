# SPDX-License-Identifier: Apache-2.0
# Generates the C++ bindings of one EXPRESS schema and compiles them
# (syntax only, warnings as errors) against the runtime headers, so a test
# can show that names and constructs of a schema give bindings that build.
#
#   cmake -DEXPRESSC=... -DSCHEMA=file.exp -DOUT=dir -DCXX=c++ -DINCLUDES="a;b" -P compile_bindings.cmake
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
execute_process(COMMAND "${EXPRESSC}" --cpp-out "${OUT}" "${SCHEMA}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "expressc failed on ${SCHEMA} (${status})")
endif()
file(GLOB sources "${OUT}/*.cc")
set(include_flags "-I${OUT}")
foreach(dir IN LISTS INCLUDES)
  list(APPEND include_flags "-I${dir}")
endforeach()
foreach(source IN LISTS sources)
  execute_process(COMMAND "${CXX}" -std=c++20 -fsyntax-only -Wall -Wextra -Werror ${include_flags} "${source}"
                  RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "the bindings generated for ${SCHEMA} do not compile: ${source}")
  endif()
endforeach()
