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

HeightMap::HeightMap(double x0_, double y0_, double x1, double y1, double top_, double floor_, double cell_)
    : x0(x0_), y0(y0_), cell(cell_), top(top_), floor(floor_), nx(static_cast<int>((x1 - x0_) / cell_)),
      ny(static_cast<int>((y1 - y0_) / cell_)), h(static_cast<std::size_t>(nx * ny), top_) {}

void HeightMap::cut(const gcode::Result& motion, const std::map<int, double>& radius) {
  machining::Vec3 at{0, 0, 0};
  for (const gcode::Call& call : motion.calls) {
    if (call.kind != gcode::CallKind::rapid && call.kind != gcode::CallKind::linear && call.kind != gcode::CallKind::arc)
      continue;
    machining::Move move;
    move.from = at;
    move.to = {call.v[0], call.v[1], call.kind == gcode::CallKind::arc ? call.v[5] : call.v[2]};
    at = move.to;
    if (call.kind == gcode::CallKind::rapid) continue;
    const auto r = radius.find(call.state.tool);
    REQUIRE(r != radius.end());
    std::vector<machining::Vec3> points;
    if (call.kind == gcode::CallKind::arc) {
      move.kind = machining::Move::Kind::arc;
      move.centre = {call.v[2], call.v[3], 0};
      move.rotation = static_cast<int>(std::lround(call.v[4]));
      points = machining::arc_points(move, cell / 2);
    } else {
      const double len = std::hypot(move.to.x - move.from.x, move.to.y - move.from.y, move.to.z - move.from.z);
      const int n = std::max(1, static_cast<int>(std::ceil(len / (cell / 2))));
      for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        points.push_back({move.from.x + (move.to.x - move.from.x) * t, move.from.y + (move.to.y - move.from.y) * t,
                          move.from.z + (move.to.z - move.from.z) * t});
      }
    }
    for (const auto& p : points) {
      const double rr = r->second;
      for (int j = std::max(0, static_cast<int>((p.y - rr - y0) / cell)); j < std::min(ny, static_cast<int>((p.y + rr - y0) / cell) + 2); ++j)
        for (int i = std::max(0, static_cast<int>((p.x - rr - x0) / cell)); i < std::min(nx, static_cast<int>((p.x + rr - x0) / cell) + 2); ++i) {
          const double cx = x0 + (i + 0.5) * cell, cy = y0 + (j + 0.5) * cell;
          if ((cx - p.x) * (cx - p.x) + (cy - p.y) * (cy - p.y) > rr * rr) continue;
          double& cellz = h[static_cast<std::size_t>(j * nx + i)];
          cellz = std::max(floor, std::min(cellz, p.z));
        }
    }
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
