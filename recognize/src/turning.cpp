// SPDX-License-Identifier: Apache-2.0
// Seed 002 (G2STEP), the order of §3.2: pre-processor, operations (they
// need tool and technology), features and strategies (they need the
// operation), then the Part 21 project.
#include <fmt/format.h>

#include "importers.h"
#include "turning_steps.h"

namespace stepnc::recognize {

void import_turning(const gcode::Result& result, const gcode::Program& program, const ImportOptions& options,
                    ImportResult& out) {
  using namespace turning;
  std::vector<std::uint32_t> compensated_lines;
  if (!read_compensation(result, program, options, out, compensated_lines)) return;
  Motion motion;
  if (!read_motion(result, program, motion, options, out)) return;
  std::vector<Group> groups = divide(motion, result, *options.tools);
  if (groups.empty()) {
    out.errors.push_back(fmt::format("{}: error: the program moves no tool: nothing to import", options.program_file));
    return;
  }
  // Setup workingsteps join the operation workingstep they prepare.
  for (const auto& [before, decision] : motion.setup)
    for (Group& group : groups)
      if (before < group.end_move()) {
        group.decisions.insert(group.decisions.begin(), decision);
        break;
      }

  for (Group& group : groups)
    for (std::size_t i = group.first_move(); i < group.end_move(); ++i)
      if (motion.moves[i].kind == Move::Kind::feed) {
        group.cut.add(motion.moves[i].from);
        group.cut.add(motion.moves[i].to);
      }
  std::vector<Recognised> ops(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const tooling::Tool* tool = options.tools->find(groups[g].tool);
    if (!tool) {  // the front end checked every T; a move before any T has none
      out.errors.push_back(fmt::format("{}:{}: error: motion with no tool loaded (T{})", options.program_file,
                                       motion.moves[groups[g].first_move()].line, groups[g].tool));
      return;
    }
    if (auto decision = compensation_decision(groups[g], motion, *tool, compensated_lines))
      groups[g].decisions.push_back(std::move(*decision));
    recognise_operation(groups[g], groups, g, std::span<const Recognised>(ops.data(), g), motion, result, *tool, ops[g], groups[g].decisions);
  }
  Workpiece workpiece = estimate_stock(motion, groups, ops, options, groups.front().decisions);
  const Workpiece& stock = workpiece;  // write_model reads only the stock cylinder
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const tooling::Tool& tool = *options.tools->find(groups[g].tool);
    const Point top = workpiece.top();
    recognise_feature(groups[g], motion, tool, workpiece, ops[g], groups[g].decisions);
    recognise_strategy(groups[g], motion, tool, top, ops[g], groups[g].decisions);
  }
  out.header.schemas = {"MACHINING_SCHEMA", "TURNING_SCHEMA", "TURNING_MACHINE_TOOL_SCHEMA", "MILLING_SCHEMA",
                        "MILLING_MACHINE_TOOL_SCHEMA"};
  out.model = write_model(motion, groups, ops, stock, options, out.steps);
}

}  // namespace stepnc::recognize
