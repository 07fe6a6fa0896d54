// SPDX-License-Identifier: Apache-2.0
#include "stepnc/tooling/typed_tool.h"

#include <fmt/format.h>

#include "milling_machine_tool_schema.h"
#include "turning_machine_tool_schema.h"

namespace stepnc::tooling {

namespace ms = machining_schema;
namespace mt = milling_machine_tool_schema;
namespace tt = turning_machine_tool_schema;

machining_schema::cutting_tool& write_typed_tool(meta::Model& model, const Tool& tool) {
  auto& edge = model.create<ms::cutting_component>();
  edge.tool_offset_length = tool.length.value_or(0);
  ms::cutting_tool* made = nullptr;
  if (tool.kind == "center_drill" || tool.kind == "twist_drill" || tool.kind == "drill") {
    auto& dimension = model.create<mt::milling_tool_dimension>();
    dimension.diameter = tool.diameter.value_or(0);
    mt::milling_machine_tool_body* body = nullptr;
    if (tool.kind == "center_drill")
      body = &model.create<mt::center_drill>();
    else
      body = &model.create<mt::twist_drill>();
    body->dimension = &dimension;
    body->number_of_teeth = tool.flutes.value_or(2);
    auto& cutter = model.create<mt::milling_cutting_tool>();
    cutter.its_tool_body = body;
    made = &cutter;
  } else {
    auto& dimension = model.create<tt::turning_tool_dimension>();
    dimension.nose_radius = tool.nose_radius;
    dimension.side_cutting_edge_angle = tool.side_cutting_edge_angle;
    dimension.end_cutting_edge_angle = tool.end_cutting_edge_angle;
    dimension.cutting_edge_length = tool.cutting_edge_length;
    tt::turning_machine_tool_body* body = nullptr;
    if (tool.kind == "grooving_tool") {
      auto& groover = model.create<tt::grooving_tool>();
      groover.cutting_width = tool.width.value_or(0);
      body = &groover;
    } else {
      body = &model.create<tt::general_turning_tool>();
    }
    body->dimension = &dimension;
    if (tool.hand == "left") body->hand_of_tool = tt::hand_of_tool_type::left;
    else if (tool.hand == "neutral") body->hand_of_tool = tt::hand_of_tool_type::neutral;
    else if (tool.hand == "right") body->hand_of_tool = tt::hand_of_tool_type::right;
    auto& cutter = model.create<tt::turning_machine_tool>();
    cutter.its_tool_body = body;
    made = &cutter;
  }
  made->its_id = tool.name.empty() ? fmt::format("T{}", tool.number) : tool.name;
  made->its_cutting_edge = {&edge};
  if (tool.length) made->overall_assembly_length = tool.length;
  return *made;
}

}  // namespace stepnc::tooling
