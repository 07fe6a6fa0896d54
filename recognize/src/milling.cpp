// SPDX-License-Identifier: Apache-2.0
// Seed 004 (G-code -> STEP-NC): the milling rule set behind import_program.
#include <algorithm>

#include <fmt/format.h>

#include "importers.h"
#include "milling.h"

namespace stepnc::recognize {

namespace milling {

double Tools::radius(int number) const {
  const tooling::Tool* tool = find(number);
  return tool && tool->diameter ? *tool->diameter / 2 : 0;
}

std::string Tools::kind(int number) const {
  const tooling::Tool* tool = find(number);
  return tool ? tool->kind : "";
}

bool Tools::drill_like(int number) const {
  const std::string k = kind(number);
  return k == "twist_drill" || k == "drill" || k == "center_drill" || k == "centerdrill" || k == "reamer" ||
         k == "tapered_reamer" || k == "tap" || k == "countersink" || k == "boring_tool";
}

}  // namespace milling

void import_milling(const gcode::Result& motion, const ImportOptions& options, ImportResult& result) {
  using namespace milling;
  const Tools tools{options.tools};
  Recognised recognised;
  // The top of the part: the stock's, else the program's Z0 (SEEDS-SPEC
  // 4.2.6: Fig. 10 is zeroed on the top face).
  recognised.top_z = options.stock && options.stock->shape == Stock::Shape::block
                         ? options.stock->origin_z + options.stock->size_z
                         : 0;
  if (options.stock && options.stock->shape == Stock::Shape::block) {
    const Stock& b = *options.stock;
    recognised.stock_top = machining::polygons::make_area({{b.origin_x, b.origin_y},
                                                           {b.origin_x + b.size_x, b.origin_y},
                                                           {b.origin_x + b.size_x, b.origin_y + b.size_y},
                                                           {b.origin_x, b.origin_y + b.size_y}});
  }
  // The security plane: the highest rapid (Fig. 10 L2 "secure plane" Z100).
  bool any_rapid = false;
  for (const gcode::Call& call : motion.calls)
    if (call.kind == gcode::CallKind::rapid) {
      recognised.security_z = any_rapid ? std::max(recognised.security_z, call.v[2]) : call.v[2];
      any_rapid = true;
    }
  const std::vector<Section> sections = segment(motion);
  for (const Section& section : sections) {
    const int tool = section.setting.tool;
    if (tool != 0 && !tools.find(tool)) {
      result.errors.push_back(fmt::format("{}:{}: error: T{} cuts but the tool list {} does not describe it",
                                          options.program_file, section.first_line, tool, options.tools_file));
      return;
    }
    if (!section.cycles.empty() || tools.drill_like(tool) || !section.runs.empty()) {
      if (tool == 0) {
        result.errors.push_back(fmt::format("{}:{}: error: the program cuts before any tool is selected (no T word)",
                                            options.program_file, section.first_line));
        return;
      }
      if (tools.radius(tool) <= 0) {
        result.errors.push_back(fmt::format("{}: error: tool {} (line {}) has no diameter; the importer needs it",
                                            options.tools_file, tool, tools.find(tool)->line));
        return;
      }
    }
    recognise_holes(section, tools, options, recognised);
    recognise_milling(section, tools, options, recognised);
  }
  if (recognised.operations.empty()) {
    result.errors.push_back(fmt::format("{}: error: the program cuts nothing (no feed move, no canned cycle)",
                                        options.program_file));
    return;
  }
  finish_features(tools, options, recognised);
  // ISO 14649-10: the retract plane lies above the feature's top; the
  // program's (its approach's start) kept under the security plane, so
  // posting the import again is not refused.
  for (Operation& op : recognised.operations) {
    const double top = recognised.features[op.feature].origin.z;
    op.retract_plane = std::min(std::max(0.0, op.retract_plane - top), std::max(0.0, recognised.security_z - top));
  }
  keep_typed_where_reproduced(tools, options, recognised);
  write_model(recognised, tools, options, result);
  for (const Operation& op : recognised.operations) {
    const Feature& feature = recognised.features[op.feature];
    ImportedStep step;
    step.workingstep = "WS " + op.id;
    step.operation = op.entity;
    step.feature = fmt::format("{} {}", feature.entity, feature.id);
    step.tool = op.tool;
    step.first_line = op.first_line;
    step.last_line = op.last_line;
    // The feature's decisions with its first operation, then the operation's.
    if (feature.operations.front() == static_cast<std::size_t>(&op - recognised.operations.data()))
      step.decisions = feature.decisions;
    step.decisions.insert(step.decisions.end(), op.decisions.begin(), op.decisions.end());
    result.steps.push_back(std::move(step));
  }
}

}  // namespace stepnc::recognize
