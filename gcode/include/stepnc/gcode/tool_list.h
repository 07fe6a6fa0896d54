// SPDX-License-Identifier: Apache-2.0
// Tool lists in the shop's one CSV format (shared/formats/tool-list.md):
// G-code carries tool numbers; the list gives their geometry.
#pragma once

#include <map>
#include <string_view>
#include <vector>

#include "stepnc/gcode/interpreter.h"

namespace stepnc::gcode {

struct ToolList {
  std::map<int, Tool> tools;
  std::vector<Diagnostic> errors;  // line:column of the bad cell; an unknown column is an error
  bool ok() const { return errors.empty(); }
};

ToolList read_tool_list(std::string_view csv);

}  // namespace stepnc::gcode
