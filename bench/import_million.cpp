// SPDX-License-Identifier: Apache-2.0
// Importing a one-million-block milling program (stepnc import, seed 004's
// rules) against the G-code interpretation alone, measured in the same run
// on the same text: a 3-axis spiral of 1 M points (the shape of
// post_million's toolpath, so it becomes one freeform operation whose
// cutter-location data holds every point), and a 2.5D pocket program of
// 1 M blocks (rings in layers 0.1 mm apart) whose layers are read through
// Clipper (a path repeated on many layers is swept once).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include "support.h"
#include "stepnc/gcode/controller.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/recognize/import.h"

namespace {

std::string spiral(std::size_t blocks) {
  std::string out = "G21 G17 G90 G94\nT1 M6\nS8000 M3\nF3000\nG0 X5 Y0 Z5\n";
  for (std::size_t i = 0; i + 7 < blocks; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(blocks);
    const double angle = t * 2000 * 3.14159265358979, radius = 5 + 50 * t;
    fmt::format_to(std::back_inserter(out), "G1 X{:.4f} Y{:.4f} Z{:.4f}\n", radius * std::cos(angle),
                   radius * std::sin(angle), -1 - 2 * t);
  }
  out += "M5\nM2\n";
  return out;
}

// Contour-parallel rings of a 100 x 60 pocket, 2 mm apart, in layers of 1 mm.
std::string pocket(std::size_t blocks) {
  std::string out = "G21 G17 G90 G94\nT1 M6\nS8000 M3\nF1200\nG0 X50 Y30 Z5\n";
  std::size_t n = 5;
  for (int layer = 1; n < blocks; ++layer) {
    fmt::format_to(std::back_inserter(out), "G1 Z{}\n", -layer * 0.1);
    ++n;
    for (double d = 1; d <= 24 && n < blocks; d += 2, n += 5)
      fmt::format_to(std::back_inserter(out), "X{0} Y{1}\nX{2}\nY{3}\nX{0}\nY30\n", 50 - d, 30 - d, 50 + 20 + d, 30 + d);
    out += "G0 Z5\nX50 Y30\n";
    n += 2;
  }
  out += "M5\nM2\n";
  return out;
}

void measure(const char* name, const std::string& program, int runs) {
  const auto controller = *stepnc::gcode::controller("rs274ngc");
  const auto tools = stepnc::tooling::read_tool_list("tool,kind,diameter,length\n1,endmill,6,0\n", "tools.csv");
  stepnc::gcode::Options options;
  options.tools = {{1, {1, 0, 6}}};
  std::size_t calls = 0, steps = 0, instances = 0;
  const double interpret = stepnc_bench::best_time(runs, [&] {
    const auto result = stepnc::gcode::interpret_text(program, controller, options);
    if (!result.ok()) std::abort();
    calls = result.calls.size();
  });
  stepnc::recognize::ImportOptions import;
  import.controller = "rs274ngc";
  import.tools = &tools;
  import.program_file = "bench.ngc";
  const double full = stepnc_bench::best_time(runs, [&] {
    const auto result = stepnc::recognize::import_program(program, import);
    if (!result.ok()) std::abort();
    steps = result.steps.size();
    instances = result.model->size();
  });
  const auto lines = static_cast<std::size_t>(std::count(program.begin(), program.end(), '\n'));
  fmt::print("{}: {} blocks, {} calls, {} workingsteps, {} instances\n", name, lines, calls, steps, instances);
  fmt::print("  gcode interpretation alone: {:7.3f} s\n", interpret);
  fmt::print("  stepnc import (interpret + rules + model): {:7.3f} s  {:.2f}x the interpretation\n", full, full / interpret);
}

}  // namespace

int main() {
  measure("3-axis spiral (freeform)", spiral(1'000'000), 3);
  measure("2.5D pocket layers (Clipper)", pocket(1'000'000), 3);
  return 0;
}
