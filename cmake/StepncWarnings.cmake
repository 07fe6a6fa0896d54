# SPDX-License-Identifier: Apache-2.0
# Our own targets build with these warnings; third-party generated code
# (the ANTLR parser) is compiled without them, since we do not own it.
function(stepnc_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
endfunction()
