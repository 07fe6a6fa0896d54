// SPDX-License-Identifier: Apache-2.0
// Importing a 100,000-block Fanuc lathe program (seed 002: pre-processor,
// Table 3, swept areas and Booleans, Table 4, Table 5, the typed model),
// against the baseline measured in the same run: the G-code interpretation
// alone, which the import starts with.
#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <string>

#include "stepnc/gcode/controller.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/recognize/import.h"
#include "support.h"

namespace {

constexpr std::size_t target_blocks = 100'000;

// A shop-sized program: face, rough the outside in passes, finish a wavy
// contour in many short blocks (as CAM writes it), groove, drill, bore;
// repeated for parts along a bar until the block count is reached.
std::string lathe_program(std::size_t& blocks) {
  std::string out = "O1\nG21 G40 G99\nG50 S2500\n";
  blocks = 3;
  auto add = [&](std::string line) {
    out += line;
    out += '\n';
    ++blocks;
  };
  for (int part = 0; blocks + 10 < target_blocks; ++part) {
    const double z0 = -200.0 * part;  // each part 200 mm further along the bar (one setup: coordinates unchanged)
    add("T0101");
    add("G96 S200 M03 M08");
    add(fmt::format("G00 X84. Z{:.3f}", z0 + 3));
    for (int pass = 0; pass < 3; ++pass) {
      const double z = z0 + 2 - 0.7 * (pass + 1);
      add(fmt::format("G00 Z{:.3f}", z));
      add("G01 X-1.6 F0.25");
      add(fmt::format("G00 X0.4 Z{:.3f}", z + 1));
      add("X84.");
    }
    add(fmt::format("G00 X82. Z{:.3f}", z0 + 2));
    double previous = 80;
    for (double x = 77.5; x > 50; x -= 2.5) {
      add(fmt::format("G00 X{:.3f}", x));
      add(fmt::format("G01 Z{:.3f} F0.3", z0 - 120));
      add(fmt::format("X{:.3f}", previous));
      add(fmt::format("G00 X{:.3f} Z{:.3f}", previous + 2, z0 + 2));
      previous = x;
    }
    add("T0202");
    add("G96 S250 M03");
    add(fmt::format("G00 X48. Z{:.3f}", z0 + 2));
    add(fmt::format("G01 Z{:.3f} F0.1", z0));
    const int points = 6000;
    for (int i = 1; i <= points && blocks + 40 < target_blocks; ++i) {
      const double z = z0 - 120.0 * i / points;
      add(fmt::format("X{:.4f} Z{:.4f}", 48 + 1.5 * std::sin(z * 0.3) + 0.02 * i / points, z));
    }
    add(fmt::format("G01 X82. Z{:.3f}", z0 - 121));
    add(fmt::format("G00 X100. Z{:.3f}", z0 + 50));
    add("T0303");
    add("G97 S800 M03");
    add(fmt::format("G00 X54. Z{:.3f}", z0 - 40));
    add("G01 X44. F0.05");
    add("G04 P500");
    add("G00 X54.");
    add("T0404");
    add("G97 S600 M03");
    add(fmt::format("G00 X0. Z{:.3f}", z0 + 3));
    for (int peck = 1; peck <= 4; ++peck) {
      if (peck > 1) add(fmt::format("G00 Z{:.3f}", z0 - 10.0 * (peck - 1) + 1));
      add(fmt::format("G01 Z{:.3f} F0.12", z0 - 10.0 * peck));
      add(fmt::format("G00 Z{:.3f}", z0 + 3));
    }
    add(fmt::format("G00 X100. Z{:.3f}", z0 + 50));
  }
  out += "M05 M09\nM30\n";
  blocks += 2;
  return out;
}

}  // namespace

int main() {
  std::size_t blocks = 0;
  const std::string program = lathe_program(blocks);
  const std::string csv =
      "tool,kind,name,holder,insert,diameter,width,cutting_edge_length,hand\n"
      "1,general_turning_tool,ROUGH,PCLNR2525M12,CNMG120408,,,,right\n"
      "2,general_turning_tool,FINISH,SVJBR2525M16,VBMM160404,,,,right\n"
      "3,grooving_tool,GROOVE 3,,,,3,12,neutral\n"
      "4,twist_drill,DRILL 20,,,20,,,right\n";
  const stepnc::tooling::ToolList tools = stepnc::tooling::read_tool_list(csv, "bench.csv");
  if (!tools.ok()) std::abort();
  const auto lathe = *stepnc::gcode::controller("fanuc-lathe");
  stepnc::gcode::Options run;
  for (const auto& tool : tools.tools) run.tools[tool.number] = {tool.number, 0, 0};

  std::size_t calls = 0, steps = 0, instances = 0;
  const double interpret = stepnc_bench::best_time(3, [&] {
    const auto result = stepnc::gcode::interpret_text(program, lathe, run);
    if (!result.ok()) std::abort();
    calls = result.calls.size();
  });
  const double import = stepnc_bench::best_time(3, [&] {
    stepnc::recognize::ImportOptions options;
    options.controller = "fanuc-lathe";
    options.tools = &tools;
    options.program_file = "bench.nc";
    const auto result = stepnc::recognize::import_program(program, options);
    if (!result.ok()) {
      fmt::print(stderr, "{}\n", result.errors.front());
      std::abort();
    }
    steps = result.steps.size();
    instances = result.model->instances().size();
  });
  fmt::print("program: {} blocks, {:.1f} MB, {} calls -> {} workingsteps, {} instances\n", blocks,
             static_cast<double>(program.size()) / 1e6, calls, steps, instances);
  fmt::print("baseline, gcode interpretation alone:   {:8.3f} s\n", interpret);
  fmt::print("stepnc import (interpretation + seed 002 rules + model): {:8.3f} s, {:.1f}x the baseline\n", import,
             import / interpret);
  return 0;
}
