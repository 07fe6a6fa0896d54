// SPDX-License-Identifier: Apache-2.0
#include "milling_test_support.h"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "stepnc/machining/generate.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/machining/motion.h"
#include "stepnc/post/dialect.h"

namespace stepnc_test::milling {

using namespace stepnc;

std::string sample_text(const std::string& relative) {
  std::ifstream in(std::string(STEPNC_SOURCE_DIR) + "/samples/" + relative, std::ios::binary);
  REQUIRE(in);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Imported import(const std::string& program, const std::string& tools_csv, const std::string& controller,
                const std::string& stock) {
  Imported out;
  out.tools = tooling::read_tool_list(tools_csv, "tools.csv");
  REQUIRE(out.tools.ok());
  recognize::ImportOptions options;
  options.controller = controller;
  options.tools = &out.tools;
  options.tools_file = "tools.csv";
  options.program_file = "program.nc";
  if (!stock.empty()) {
    std::string error;
    options.stock = recognize::parse_stock(stock, error);
    REQUIRE(options.stock);
  }
  out.result = recognize::import_program(program, options);
  return out;
}

void cut(machining::HeightMap& map, const gcode::Result& motion, const std::map<int, double>& radius) {
  machining::Vec3 at{0, 0, 0};
  for (const gcode::Call& call : motion.calls) {
    if (call.kind != gcode::CallKind::rapid && call.kind != gcode::CallKind::linear && call.kind != gcode::CallKind::arc)
      continue;
    machining::Move move;
    move.kind = call.kind == gcode::CallKind::arc ? machining::Move::Kind::arc : machining::Move::Kind::feed;
    move.from = at;
    move.to = {call.v[0], call.v[1], call.kind == gcode::CallKind::arc ? call.v[5] : call.v[2]};
    at = move.to;
    if (call.kind == gcode::CallKind::rapid) continue;
    const auto r = radius.find(call.state.tool);
    REQUIRE(r != radius.end());
    if (call.kind == gcode::CallKind::arc) {
      move.centre = {call.v[2], call.v[3], 0};
      move.rotation = static_cast<int>(std::lround(call.v[4]));
    }
    map.cut(move, r->second);
  }
}

Posted post(const meta::Model& model, const std::string& dialect) {
  const auto described = machining::describe_project(model);
  for (const auto& d : described.diagnostics) INFO(d.message);
  REQUIRE(described.ok());
  const auto generated = machining::generate(described.project);
  REQUIRE(generated.ok());
  Posted out;
  out.text = post::print(generated.program, *post::dialect_from_name(dialect)).text;
  out.tools_csv = "tool,kind,diameter,length\n";
  for (const auto& entry : generated.program.tools) {
    using machining::ToolKind;
    const ToolKind k = entry.tool.kind;
    const char* kind = k == ToolKind::facemill      ? "facemill"
                       : k == ToolKind::twist_drill ? "twist_drill"
                       : k == ToolKind::center_drill ? "center_drill"
                       : k == ToolKind::tap          ? "tap"
                       : k == ToolKind::reamer       ? "reamer"
                       : k == ToolKind::boring_tool  ? "boring_tool"
                       : k == ToolKind::ball_end_mill ? "ballnose_endmill"
                       : k == ToolKind::bull_nose_end_mill ? "bullnose_endmill"
                                                     : "endmill";
    out.tools_csv += fmt::format("{},{},{},0\n", entry.number, kind, entry.tool.diameter);
  }
  return out;
}

}  // namespace stepnc_test::milling
