// SPDX-License-Identifier: Apache-2.0
#include "stepnc/control/units.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <variant>

namespace stepnc::control {

namespace m = machining;

bool StepProgram::ok() const {
  return std::none_of(diagnostics.begin(), diagnostics.end(),
                      [](const m::Diagnostic& d) { return d.severity == m::Diagnostic::Severity::error; });
}

namespace {

double distance(const m::Vec3& a, const m::Vec3& b) { return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z); }

bool is_cut(const m::Statement& s) {
  return std::holds_alternative<m::Linear>(s) || std::holds_alternative<m::Arc>(s) ||
         std::holds_alternative<m::DrillCycle>(s);
}

}  // namespace

StepProgram generate_step(const m::MachiningProject& project, const m::Executable& step, bool tool_ready) {
  m::MachiningProject alone = project;
  alone.main_workplan = m::Executable{};
  alone.main_workplan.kind = m::ExecutableKind::workplan;
  alone.main_workplan.source = project.main_workplan.source;
  alone.main_workplan.setup_security_plane = project.main_workplan.setup_security_plane;
  alone.main_workplan.children = {step};
  m::GenerateOptions options;
  options.tool_ready = tool_ready;
  m::GenerateResult generated = m::generate(alone, options);
  StepProgram out;
  out.diagnostics = std::move(generated.diagnostics);
  if (!out.ok()) return out;
  // Feature cycles go; the explicit blocks they replace stay.
  std::erase_if(generated.program.blocks,
                [](const m::Block& block) { return std::holds_alternative<m::FeatureCycle>(block.statement); });
  out.program = std::move(generated.program);
  const std::vector<m::Block>& blocks = out.program.blocks;

  // The program start: the leading comments and tolerance of the program
  // itself (an NC function's own blocks carry no provenance either).
  while (out.start_end < blocks.size() && blocks[out.start_end].provenance == 0 &&
         (std::holds_alternative<m::Comment>(blocks[out.start_end].statement) ||
          std::holds_alternative<m::Tolerance>(blocks[out.start_end].statement)))
    ++out.start_end;
  out.epilogue_begin = blocks.size();
  while (out.epilogue_begin > out.start_end && blocks[out.epilogue_begin - 1].provenance == 0) --out.epilogue_begin;

  // Units: a unit begins at the first rapid after a cut (or the first rapid
  // of the executable) that leads to another cut.
  std::vector<std::size_t> starts;
  bool cut_since_start = true;
  std::size_t candidate = out.start_end;
  bool have_candidate = false;
  for (std::size_t i = out.start_end; i < out.epilogue_begin; ++i) {
    const m::Statement& s = blocks[i].statement;
    if (std::holds_alternative<m::Rapid>(s) && cut_since_start && !have_candidate) {
      candidate = i;
      have_candidate = true;
    } else if (is_cut(s)) {
      if (std::holds_alternative<m::DrillCycle>(s) && !have_candidate) {
        candidate = i;
        have_candidate = true;
      }
      if (have_candidate) {
        starts.push_back(candidate);
        have_candidate = false;
        cut_since_start = false;
      }
      if (std::holds_alternative<m::DrillCycle>(s)) cut_since_start = true;
    }
    if (std::holds_alternative<m::Linear>(s) || std::holds_alternative<m::Arc>(s)) cut_since_start = true;
  }
  out.prologue_end = starts.empty() ? out.epilogue_begin : starts.front();

  // Layers by cutting depth, in order of first appearance; time by length and feed.
  std::map<long long, int> layer_of_depth;
  std::map<int, int> passes;
  double feed = 0;
  m::Vec3 at{0, 0, out.program.clear_z};
  for (std::size_t u = 0; u < starts.size(); ++u) {
    UnitFeature unit;
    unit.first = starts[u];
    unit.end = u + 1 < starts.size() ? starts[u + 1] : out.epilogue_begin;
    std::optional<double> depth;
    if (u == 0)
      for (std::size_t i = 0; i < unit.first; ++i)
        if (auto* f = std::get_if<m::FeedRate>(&blocks[i].statement)) feed = f->value;
    for (std::size_t i = unit.first; i < unit.end; ++i) {
      const m::Statement& s = blocks[i].statement;
      if (auto* f = std::get_if<m::FeedRate>(&s)) feed = f->value;
      if (auto* r = std::get_if<m::Rapid>(&s)) {
        unit.seconds += distance(at, r->to) / rapid_rate * 60;
        at = r->to;
      } else if (auto* l = std::get_if<m::Linear>(&s)) {
        if (feed > 0) unit.seconds += distance(at, l->to) / feed * 60;
        at = l->to;
        depth = depth ? std::min(*depth, l->to.z) : l->to.z;
      } else if (auto* a = std::get_if<m::Arc>(&s)) {
        // The chord, at least: the estimate only orders time events.
        if (feed > 0) unit.seconds += distance(at, a->to) / feed * 60;
        at = a->to;
        depth = depth ? std::min(*depth, a->to.z) : a->to.z;
      } else if (auto* d = std::get_if<m::DrillCycle>(&s)) {
        if (d->feed > 0) unit.seconds += 2 * (d->r - d->bottom) / d->feed * 60;
        depth = d->bottom;
        at = {d->x, d->y, d->r};
      } else if (auto* w = std::get_if<m::Dwell>(&s)) {
        unit.seconds += w->seconds;
      }
    }
    const long long key = std::llround(-depth.value_or(0) * 1000);
    const auto [it, added] = layer_of_depth.emplace(key, static_cast<int>(layer_of_depth.size()));
    unit.layer = it->second;
    unit.pass = passes[unit.layer]++;
    out.units.push_back(unit);
  }
  return out;
}

}  // namespace stepnc::control
