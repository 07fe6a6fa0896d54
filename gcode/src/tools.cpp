// SPDX-License-Identifier: Apache-2.0
// The shop's tool list, read by tooling/, as the interpreter uses it.
#include "stepnc/gcode/interpreter.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc::gcode {

std::map<int, Tool> tools_from(const tooling::ToolList& list) {
  std::map<int, Tool> tools;
  for (const tooling::Tool& t : list.tools)
    tools[t.number] = Tool{t.number, t.length.value_or(0), t.diameter.value_or(0), t.nose_radius.value_or(0),
                           t.tip_direction.value_or(0)};
  return tools;
}

}  // namespace stepnc::gcode
