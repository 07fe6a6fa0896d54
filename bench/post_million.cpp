// SPDX-License-Identifier: Apache-2.0
// Posting a project whose explicit toolpath has one million points: build
// the IR (generate) and print it as RS274NGC and 840D, against a baseline
// measured in the same run: formatting the same number of "G1 X Y Z"
// lines straight into a buffer with fmt.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>

#include "support.h"
#include "stepnc/post/dialect.h"
#include "stepnc/machining/generate.h"

using namespace stepnc::machining;
using namespace stepnc::post;

namespace {

constexpr std::size_t points = 1'000'000;

MachiningProject million_point_project() {
  MachiningProject p;
  p.source = {1, "ONE MILLION POINTS"};
  p.workpiece.block_min = {-60, -60, -10};
  p.workpiece.block_max = {60, 60, 0};
  p.security_plane = 20;
  Tool mill;
  mill.source = {2, "BALL 6"};
  mill.kind = ToolKind::ball_end_mill;
  mill.diameter = 6;
  mill.flutes = 2;
  p.tools.push_back(mill);
  Polyline line;
  line.points.reserve(points);
  for (std::size_t i = 0; i < points; ++i) {
    const double t = static_cast<double>(i) / points;
    const double angle = t * 2000 * 3.14159265358979, radius = 5 + 50 * t;
    line.points.push_back({radius * std::cos(angle), radius * std::sin(angle), -1 - 2 * t});
  }
  Toolpath path;
  path.source = {3, "SPIRAL"};
  path.elements.push_back(std::move(line));
  Feature area;
  area.source = {4, "AREA"};
  area.shape = PlanarFace{1, 1};
  p.features.push_back(area);
  Operation op;
  op.source = {5, "FREEFORM"};
  op.kind = OperationKind::freeform;
  op.tool = 0;
  op.technology = Technology{};
  op.technology->feedrate = 3000;
  op.technology->spindle_rpm = -8000;
  op.toolpaths.push_back(std::move(path));
  p.operations.push_back(std::move(op));
  Executable ws;
  ws.kind = ExecutableKind::workingstep;
  ws.source = {6, "WS FREEFORM"};
  ws.step = {0, 0, std::nullopt};
  p.main_workplan.children.push_back(ws);
  return p;
}

}  // namespace

int main() {
  const MachiningProject project = million_point_project();
  std::size_t sink = 0;

  const double baseline = stepnc_bench::best_time(3, [&] {
    const auto& pts = std::get<Polyline>(project.operations[0].toolpaths[0].elements[0]).points;
    fmt::memory_buffer out;
    for (const Vec3& p : pts) fmt::format_to(std::back_inserter(out), "G1 X{:.4f} Y{:.4f} Z{:.4f}\n", p.x, p.y, p.z);
    sink += out.size();
  });
  GenerateResult result;
  const double generate_s = stepnc_bench::best_time(3, [&] {
    result = generate(project);
    sink += result.program.blocks.size();
  });
  if (!result.ok()) {
    for (const auto& d : result.diagnostics) std::fprintf(stderr, "%s\n", d.to_string().c_str());
    return 1;
  }
  const double rs274_s = stepnc_bench::best_time(3, [&] { sink += print(result.program, Dialect::rs274ngc).text.size(); });
  const double siemens_s = stepnc_bench::best_time(3, [&] { sink += print(result.program, Dialect::siemens840d).text.size(); });

  std::printf("posting %zu explicit toolpath points (best of 3):\n", points);
  std::printf("  baseline: fmt, %zu \"G1 X Y Z\" lines        %8.1f ms  1.00x\n", points, baseline * 1e3);
  std::printf("  generate (project -> program IR)        %8.1f ms  %.2fx\n", generate_s * 1e3, generate_s / baseline);
  std::printf("  print rs274ngc (with traceability)      %8.1f ms  %.2fx\n", rs274_s * 1e3, rs274_s / baseline);
  std::printf("  print siemens840d (with traceability)   %8.1f ms  %.2fx\n", siemens_s * 1e3, siemens_s / baseline);
  std::printf("  generate + rs274ngc                     %8.1f ms  %.2fx\n", (generate_s + rs274_s) * 1e3,
              (generate_s + rs274_s) / baseline);
  return sink == 0 ? 1 : 0;
}
