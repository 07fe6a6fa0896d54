// SPDX-License-Identifier: Apache-2.0
// Compiled by ctest only (-fsyntax-only): every attribute is typed, so
// linking a tool where a feature is expected, or text where a length is
// expected, is a compile error. See CMakeLists.txt for the variants.
#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "stepnc/meta/model.h"

void author(stepnc::meta::Model& model) {
  auto& step = model.create<machining_schema::machining_workingstep>();
  auto& hole = model.create<machining_schema::round_hole>();
  auto& tool = model.create<milling_machine_tool_schema::milling_cutting_tool>();
  auto& point = model.create<machining_schema::cartesian_point>();
  step.its_feature = &hole;
  point.coordinates = {0.0, 0.0, 10.0};
#if defined(STEPNC_TYPING_WRONG_REFERENCE)
  step.its_feature = &tool;
#elif defined(STEPNC_TYPING_WRONG_VALUE)
  point.coordinates[0] = "ten";
#else
  static_cast<void>(tool);
#endif
}
