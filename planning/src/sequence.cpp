// SPDX-License-Identifier: Apache-2.0
#include "stepnc/planning/sequence.h"

#include <algorithm>

#include <fmt/format.h>

#include "machining_schema.h"
#include "milling_schema.h"
#include "turning_schema.h"

namespace stepnc::planning {
namespace {

namespace ms = machining_schema;
using machining::Diagnostic;
using machining::Source;

Source source_of(const ms::executable& e) { return {e.id(), e.its_id.str()}; }

const ms::project* find_project(const meta::Model& model) {
  for (const meta::Instance* i : model.instances())
    if (auto* p = dynamic_cast<const ms::project*>(i)) return p;
  return nullptr;
}

// Workingsteps in executable order, through nested workplans.
void flatten(const ms::workplan& plan, std::vector<const ms::machining_workingstep*>& out) {
  for (const ms::executable* e : plan.its_elements) {
    if (auto* ws = dynamic_cast<const ms::machining_workingstep*>(e)) out.push_back(ws);
    else if (auto* nested = dynamic_cast<const ms::workplan*>(e)) flatten(*nested, out);
  }
}

std::vector<const ms::machining_workingstep*> executable_order(const meta::Model& model) {
  std::vector<const ms::machining_workingstep*> order;
  if (const ms::project* p = find_project(model); p && p->main_workplan) flatten(*p->main_workplan, order);
  return order;
}

std::size_t tool_changes(const std::vector<const ms::machining_workingstep*>& order) {
  std::size_t changes = 0;
  const ms::machining_tool* current = nullptr;
  for (const auto* ws : order) {
    const ms::machining_tool* tool = ws->its_operation ? ws->its_operation->its_tool : nullptr;
    if (tool && tool != current) ++changes, current = tool;
  }
  return changes;
}

bool is_roughing(const ms::machining_operation* op) {
  return dynamic_cast<const turning_schema::facing_rough*>(op) ||
         dynamic_cast<const turning_schema::contouring_rough*>(op) ||
         dynamic_cast<const milling_schema::plane_rough_milling*>(op) ||
         dynamic_cast<const milling_schema::bottom_and_side_rough_milling*>(op);
}
bool is_finishing(const ms::machining_operation* op) {
  return dynamic_cast<const turning_schema::facing_finish*>(op) ||
         dynamic_cast<const turning_schema::contouring_finish*>(op) ||
         dynamic_cast<const milling_schema::plane_finish_milling*>(op) ||
         dynamic_cast<const milling_schema::bottom_and_side_finish_milling*>(op);
}
// Hole work: centre drilling (0), drilling (1), then the rest (2): counter
// sinking, reaming, boring, tapping, internal contouring.
int hole_stage(const ms::machining_operation* op) {
  if (dynamic_cast<const milling_schema::center_drilling*>(op)) return 0;
  if (dynamic_cast<const milling_schema::drilling_operation*>(op) &&
      !dynamic_cast<const milling_schema::counter_sinking*>(op))
    return 1;  // drilling, multistep drilling
  return 2;
}

// Why `later` may not run after `earlier` ("" when it may).
std::string precedence_violation(const ms::machining_workingstep& earlier, const ms::machining_workingstep& later) {
  if (earlier.its_feature != later.its_feature || !earlier.its_feature) return {};
  const auto* a = earlier.its_operation;
  const auto* b = later.its_operation;
  const auto name = [](const ms::machining_workingstep& ws) { return fmt::format("#{} '{}'", ws.id(), ws.its_id.view()); };
  if (is_finishing(a) && is_roughing(b))
    return fmt::format("finishing {} would run before roughing {} on feature #{}: roughing comes first", name(earlier),
                       name(later), earlier.its_feature->id());
  const bool holes = hole_stage(a) < 2 || hole_stage(b) < 2;
  if (holes && hole_stage(a) > hole_stage(b))
    return fmt::format("{} would run before {} on feature #{}: centre drilling, then drilling, then the rest of the "
                       "hole's work",
                       name(earlier), name(later), earlier.its_feature->id());
  return {};
}

std::string first_violation(const std::vector<const ms::machining_workingstep*>& order) {
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size(); ++j)
      if (std::string why = precedence_violation(*order[i], *order[j]); !why.empty()) return why;
  return {};
}

template <class T>
T* find_named(meta::Model& model, const std::string& name) {
  for (meta::Instance* i : model.instances()) {
    auto* t = dynamic_cast<T*>(i);
    if (!t) continue;
    if (name == fmt::format("#{}", i->id()) || t->its_id.view() == name) return t;
  }
  return nullptr;
}

class Sequencer {
 public:
  explicit Sequencer(meta::Model& model) : model_(model) {}

  SequenceResult run(const SequenceOptions& options) {
    result_.tool_changes_before = tool_changes(executable_order(model_));
    if (options.move) move(*options.move);
    if (result_.ok() && options.fewest_tool_changes) {
      for (meta::Instance* i : model_.instances())
        if (auto* plan = dynamic_cast<ms::workplan*>(i)) group_by_tool(*plan);
    }
    result_.tool_changes_after = tool_changes(executable_order(model_));
    return std::move(result_);
  }

 private:
  void refuse(Source where, std::string message) {
    result_.diagnostics.push_back({Diagnostic::Severity::error, std::move(where), std::move(message)});
  }

  ms::workplan* parent_of(const ms::executable& e) {
    for (meta::Instance* i : model_.instances())
      if (auto* plan = dynamic_cast<ms::workplan*>(i))
        if (std::find(plan->its_elements.begin(), plan->its_elements.end(), &e) != plan->its_elements.end()) return plan;
    return nullptr;
  }

  // The innermost workplan of the named setup (a main workplan and the
  // nested workplan it holds may share one), or the named workplan.
  ms::workplan* workplan_of_setup(const std::string& name) {
    std::vector<ms::workplan*> candidates;
    for (meta::Instance* i : model_.instances()) {
      auto* plan = dynamic_cast<ms::workplan*>(i);
      if (!plan || !plan->its_setup) continue;
      const bool plan_named = name == fmt::format("#{}", plan->id()) || plan->its_id.view() == name;
      const bool setup_named =
          name == fmt::format("#{}", plan->its_setup->id()) || plan->its_setup->its_id.view() == name;
      if (plan_named) return plan;
      if (setup_named) candidates.push_back(plan);
    }
    for (ms::workplan* plan : candidates) {
      const bool holds_another = std::any_of(plan->its_elements.begin(), plan->its_elements.end(), [&](auto* e) {
        return std::find(candidates.begin(), candidates.end(), e) != candidates.end();
      });
      if (!holds_another) return plan;
    }
    return nullptr;
  }

  void move(const WorkingstepMove& m) {
    auto* ws = find_named<ms::machining_workingstep>(model_, m.workingstep);
    if (!ws) return refuse({}, fmt::format("--move: no machining_workingstep '{}'", m.workingstep));
    ms::workplan* target = workplan_of_setup(m.setup);
    if (!target) return refuse(source_of(*ws), fmt::format("--to-setup: no setup '{}' with a workplan", m.setup));
    const ms::setup& setup = *target->its_setup;
    // The setup must hold the feature's workpiece (SEEDS-SPEC 1.5 item 13).
    const ms::workpiece* piece = ws->its_feature ? ws->its_feature->its_workpiece : nullptr;
    const bool holds = std::any_of(setup.its_workpiece_setup.begin(), setup.its_workpiece_setup.end(),
                                   [&](const ms::workpiece_setup* s) { return s && s->its_workpiece == piece; });
    if (!holds)
      return refuse(source_of(*ws), fmt::format("setup #{} '{}' does not hold workpiece #{} of feature #{}", setup.id(),
                                                setup.its_id.view(), piece ? piece->id() : 0,
                                                ws->its_feature ? ws->its_feature->id() : 0));
    ms::workplan* from = parent_of(*ws);
    auto elements = target->its_elements;
    std::vector<ms::executable*> from_elements = from ? from->its_elements : std::vector<ms::executable*>{};
    if (from == target) {
      elements.erase(std::find(elements.begin(), elements.end(), ws));
    } else if (from) {
      from_elements.erase(std::find(from_elements.begin(), from_elements.end(), ws));
    }
    auto at = elements.end();
    if (!m.before.empty()) {
      auto* before = find_named<ms::machining_workingstep>(model_, m.before);
      at = before ? std::find(elements.begin(), elements.end(), before) : elements.end();
      if (at == elements.end())
        return refuse(source_of(*ws), fmt::format("--before: '{}' is not a workingstep of workplan #{} '{}'", m.before,
                                                  target->id(), target->its_id.view()));
    }
    elements.insert(at, ws);
    // Try it, check the precedence rules, and undo on a refusal.
    const auto old_target = target->its_elements;
    const auto old_from = from ? from->its_elements : std::vector<ms::executable*>{};
    target->its_elements = elements;
    if (from && from != target) from->its_elements = from_elements;
    if (std::string why = first_violation(executable_order(model_)); !why.empty()) {
      target->its_elements = old_target;
      if (from && from != target) from->its_elements = old_from;
      return refuse(source_of(*ws), "move refused: " + why);
    }
    result_.changes.push_back(
        {source_of(*ws), fmt::format("moved from workplan #{} to workplan #{} '{}' of setup #{} '{}'{}",
                                     from ? from->id() : 0, target->id(), target->its_id.view(), setup.id(),
                                     setup.its_id.view(), m.before.empty() ? "" : " before " + m.before)});
  }

  // Greedy: of the workingsteps whose predecessors are placed, take the
  // first with the current tool, else the first. Other executables stay
  // where they are and split the runs.
  void group_by_tool(ms::workplan& plan) {
    const std::size_t before = tool_changes(executable_order(model_));
    const auto original = plan.its_elements;
    std::vector<ms::executable*> result;
    const ms::machining_tool* current = nullptr;
    for (std::size_t start = 0; start < original.size();) {
      auto* first = dynamic_cast<ms::machining_workingstep*>(original[start]);
      if (!first) {
        result.push_back(original[start++]);
        continue;
      }
      std::vector<const ms::machining_workingstep*> run;
      while (start < original.size())
        if (auto* ws = dynamic_cast<ms::machining_workingstep*>(original[start])) run.push_back(ws), ++start;
        else break;
      while (!run.empty()) {
        std::size_t pick = run.size();
        for (std::size_t i = 0; i < run.size(); ++i) {
          bool available = true;
          for (std::size_t k = 0; k < i && available; ++k) available = precedence_violation(*run[i], *run[k]).empty();
          if (!available) continue;
          if (pick == run.size()) pick = i;
          if (run[i]->its_operation && run[i]->its_operation->its_tool == current) {
            pick = i;
            break;
          }
        }
        const auto* chosen = run[pick];
        if (chosen->its_operation && chosen->its_operation->its_tool) current = chosen->its_operation->its_tool;
        result.push_back(const_cast<ms::machining_workingstep*>(chosen));
        run.erase(run.begin() + static_cast<std::ptrdiff_t>(pick));
      }
    }
    if (result == original) return;
    plan.its_elements = result;
    const std::size_t after = tool_changes(executable_order(model_));
    if (after >= before || !first_violation(executable_order(model_)).empty()) {
      plan.its_elements = original;
      return;
    }
    result_.changes.push_back({source_of(plan), fmt::format("reordered for fewest tool changes: {} -> {}", before, after)});
  }

  meta::Model& model_;
  SequenceResult result_;
};

}  // namespace

bool SequenceResult::ok() const {
  return std::none_of(diagnostics.begin(), diagnostics.end(),
                      [](const Diagnostic& d) { return d.severity == Diagnostic::Severity::error; });
}

SequenceResult resequence(meta::Model& model, const SequenceOptions& options) { return Sequencer(model).run(options); }

std::size_t count_tool_changes(const meta::Model& model) { return tool_changes(executable_order(model)); }

}  // namespace stepnc::planning
