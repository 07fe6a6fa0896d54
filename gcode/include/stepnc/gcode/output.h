// SPDX-License-Identifier: Apache-2.0
// The interpreter's result for people and programs: JSON and an SVG plot.
#pragma once

#include <string>

#include "stepnc/gcode/interpreter.h"

namespace stepnc::gcode {

// {"calls": [...], "cycles": [...], "errors": [...]}: every call with its
// kind, source line, block index, values (mm, mm/min, s) and modal state.
std::string json_text(const Result& result);

// The toolpath seen from +Z (XY), or from +Y (XZ, Z across) when the
// program works in G18: rapids dashed red, feeds blue, arcs as arcs.
std::string plot_svg(const Result& result);

}  // namespace stepnc::gcode
