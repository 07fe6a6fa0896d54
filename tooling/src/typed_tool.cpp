// SPDX-License-Identifier: Apache-2.0
#include "stepnc/tooling/typed_tool.h"

#include <fmt/format.h>

#include "milling_machine_tool_schema.h"
#include "turning_machine_tool_schema.h"

namespace stepnc::tooling {

namespace ms = machining_schema;
namespace mt = milling_machine_tool_schema;
namespace tt = turning_machine_tool_schema;

bool is_milling_kind(std::string_view kind) {
  for (const std::string_view milling : {"endmill", "bullnose_endmill", "ballnose_endmill", "ball_endmill", "facemill",
                                         "twist_drill", "drill", "center_drill", "centerdrill", "reamer",
                                         "tapered_reamer", "tap", "countersink"})
    if (kind == milling) return true;
  return false;
}

machining_schema::cutting_tool& write_typed_tool(meta::Model& model, const Tool& tool, bool milling) {
  auto& edge = model.create<ms::cutting_component>();
  edge.tool_offset_length = tool.length.value_or(0);
  ms::cutting_tool* made = nullptr;
  if (milling) {
    const std::string_view kind = tool.kind;
    mt::milling_machine_tool_body* body = nullptr;
    if (kind == "twist_drill" || kind == "drill") body = &model.create<mt::twist_drill>();
    else if (kind == "center_drill" || kind == "centerdrill") body = &model.create<mt::center_drill>();
    else if (kind == "reamer") body = &model.create<mt::reamer>();
    else if (kind == "tapered_reamer") body = &model.create<mt::tapered_reamer>();
    else if (kind == "tap") body = &model.create<mt::tap>();
    else if (kind == "countersink") body = &model.create<mt::countersink>();
    else if (kind == "boring_tool") body = &model.create<mt::boring_tool>();
    else if (kind == "facemill") body = &model.create<mt::facemill>();
    else if (kind == "ballnose_endmill" || kind == "ball_endmill") body = &model.create<mt::ball_endmill>();
    else if (kind == "bullnose_endmill") body = &model.create<mt::bullnose_endmill>();
    else body = &model.create<mt::endmill>();
    auto& dimension = model.create<mt::milling_tool_dimension>();
    dimension.diameter = tool.diameter.value_or(0);
    if (kind == "twist_drill" || kind == "drill") dimension.tool_tip_half_angle = 59;  // the usual 118 degree point
    if (tool.corner_radius) dimension.edge_radius = *tool.corner_radius;
    body->dimension = &dimension;
    if (tool.flutes) body->number_of_teeth = *tool.flutes;
    else if (kind == "twist_drill" || kind == "drill" || kind == "center_drill" || kind == "centerdrill")
      body->number_of_teeth = 2;
    if (!tool.hand.empty())
      body->hand_of_cut = tool.hand == "left" ? mt::hand::left : tool.hand == "neutral" ? mt::hand::neutral : mt::hand::right;
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
