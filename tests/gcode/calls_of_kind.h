// SPDX-License-Identifier: Apache-2.0
// The calls of one kind in a result, in order (shared by the gcode tests).
#pragma once

#include <vector>

#include "stepnc/gcode/interpreter.h"

inline std::vector<const stepnc::gcode::Call*> of(const stepnc::gcode::Result& r, stepnc::gcode::CallKind kind) {
  std::vector<const stepnc::gcode::Call*> out;
  for (const auto& c : r.calls)
    if (c.kind == kind) out.push_back(&c);
  return out;
}
