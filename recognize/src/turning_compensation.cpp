// SPDX-License-Identifier: Apache-2.0
// G41/G42 tool nose radius compensation (Fanuc 0i-TF). The front end runs
// it with the tool list's nose radius and tip direction, so its calls are
// the path of the imaginary tip: the path a program written as the tip path
// by hand gives, and the one the cutting edge (Fig. 9, from the tip)
// follows. The rules read that path (project decision TN1, README); a tool
// whose nose the list does not give would make it a guess, so it is refused.
#include <algorithm>

#include <fmt/format.h>

#include "turning_steps.h"

namespace stepnc::recognize::turning {
namespace {

// The block's G40, G41 or G42 (0 when none).
int compensation_code(const gcode::Program& program, const gcode::Block& block) {
  int code = 0;
  for (std::uint32_t w = block.words_begin; w < block.words_end; ++w) {
    const gcode::Word& word = program.words[w];
    if (word.letter == 'G' && word.expr == gcode::Word::none && (word.literal == 40 || word.literal == 41 || word.literal == 42))
      code = static_cast<int>(word.literal);
  }
  return code;
}

bool motion_call(gcode::CallKind kind) {
  return kind == gcode::CallKind::rapid || kind == gcode::CallKind::linear || kind == gcode::CallKind::arc;
}

}  // namespace

bool read_compensation(const gcode::Result& result, const gcode::Program& program, const ImportOptions& options,
                       ImportResult& out, std::vector<std::uint32_t>& compensated_lines) {
  std::vector<int> code(program.blocks.size());
  bool any = false;
  for (std::size_t b = 0; b < program.blocks.size(); ++b) {
    code[b] = compensation_code(program, program.blocks[b]);
    any = any || code[b] == 41 || code[b] == 42;
  }
  if (!any) return true;
  // A block acts when execution passes it: the blocks from the previous
  // call's to this call's (only this one after a jump back: M99, GOTO).
  bool on = false;
  std::optional<std::uint32_t> previous;
  for (const gcode::Call& call : result.calls) {
    const std::uint32_t from = previous && *previous < call.block ? *previous + 1 : call.block;
    for (std::uint32_t b = from; b <= call.block && b < code.size(); ++b) {
      if (code[b] == 40) on = false;
      if (code[b] != 41 && code[b] != 42) continue;
      on = true;
      const int number = call.state.tool;
      const tooling::Tool* tool = options.tools->find(number);
      const char* missing = !tool || !tool->nose_radius ? "nose radius (nose_radius, or an ISO 1832 insert)"
                            : !tool->tip_direction     ? "tip direction (tip_direction)"
                                                       : nullptr;
      if (missing) {
        out.errors.push_back(fmt::format(
            "{}:{}: error: G{} on T{}: the tool list {}gives no {}, so the path the tool nose follows is unknown",
            options.program_file, program.blocks[b].line, code[b], number,
            options.tools_file.empty() ? "" : fmt::format("({}) ", options.tools_file), missing));
        return false;
      }
    }
    // The G40 block's move leaves the offset path: it still starts on it.
    if ((on || (call.block < code.size() && code[call.block] == 40)) && motion_call(call.kind))
      compensated_lines.push_back(call.line);
    previous = call.block;
  }
  std::sort(compensated_lines.begin(), compensated_lines.end());
  compensated_lines.erase(std::unique(compensated_lines.begin(), compensated_lines.end()), compensated_lines.end());
  return true;
}

std::optional<Decision> compensation_decision(const Group& group, const Motion& motion, const tooling::Tool& tool,
                                              const std::vector<std::uint32_t>& compensated_lines) {
  std::vector<std::uint32_t> lines;
  for (std::size_t i = group.first_move(); i < group.end_move(); ++i)
    if (std::binary_search(compensated_lines.begin(), compensated_lines.end(), motion.moves[i].line))
      lines.push_back(motion.moves[i].line);
  if (lines.empty()) return std::nullopt;
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return Decision{"G41/G42 tool nose radius compensation (Fanuc 0i-TF; project decision TN1)",
                  fmt::format("the rules read the compensated path of the imaginary tip (T{}: nose radius {:g} mm, "
                              "tip direction {}), the path the cutting edge follows, not the programmed part "
                              "contour; a program written as that tip path by hand reads the same",
                              tool.number, tool.nose_radius.value_or(0), tool.tip_direction.value_or(0)),
                  std::move(lines)};
}

}  // namespace stepnc::recognize::turning
