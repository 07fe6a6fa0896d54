// SPDX-License-Identifier: Apache-2.0
// One entry point per dialect printer.
#pragma once

#include "gcode_printer.h"

namespace stepnc::post::detail {

PrintedProgram print_rs274ngc(const Program& program);
PrintedProgram print_fanuc(const Program& program);
PrintedProgram print_siemens840d(const Program& program, const PrintOptions& options);
PrintedProgram print_canonical(const Program& program);

}  // namespace stepnc::post::detail
