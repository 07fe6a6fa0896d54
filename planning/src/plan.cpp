// SPDX-License-Identifier: Apache-2.0
#include "stepnc/planning/plan.h"

#include <algorithm>
#include <cmath>
#include <charconv>
#include <map>

#include <fmt/format.h>

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/machining/motion.h"
#include "stepnc/meta/validate.h"
#include "stepnc/tooling/typed_tool.h"
#include "turning_machine_tool_schema.h"
#include "turning_schema.h"

namespace stepnc::planning {
namespace {

namespace ms = machining_schema;
namespace mt = milling_machine_tool_schema;
namespace ts = turning_schema;
namespace tt = turning_machine_tool_schema;
using machining::Diagnostic;
using machining::OperationKind;
using machining::Source;

// ISO 14649 units (m/s, rev/s) from NC units (m/min, rev/min).
constexpr double m_per_s_per_m_per_min = 1.0 / 60;
constexpr double rev_per_s_per_rpm = 1.0 / 60;

// Cutting data late binding uses: the tool-list format carries none, so
// these are the turning sample's own (samples/turning/shaft.stp).
struct CuttingData {
  std::optional<double> cutting_speed_m_per_min;  // constant cutting speed, clamped by max_rpm
  std::optional<double> spindle_rpm;
  double feed_per_revolution = 0;  // mm/rev
};
constexpr double max_rpm = 3000;
CuttingData default_cutting_data(OperationKind kind) {
  switch (kind) {
    case OperationKind::facing_rough:
    case OperationKind::contouring_rough: return {200, std::nullopt, 0.25};
    case OperationKind::facing_finish:
    case OperationKind::contouring_finish: return {250, std::nullopt, 0.15};
    case OperationKind::grooving: return {std::nullopt, 900, 0.05};
    default: return {std::nullopt, 1200, 0.08};  // centre drilling and drilling on the lathe axis
  }
}

// The smallest feed the planner will program: a target that needs less is
// refused as impossible rather than rubbing the surface.
constexpr double min_finishing_feed = 0.01;

Source source_of(const meta::Instance& instance, std::string name) {
  return {instance.id(), std::move(name)};
}

bool is_finishing(OperationKind kind) {
  return kind == OperationKind::contouring_finish || kind == OperationKind::facing_finish;
}

// The operation kind of a typed operation, for late binding (the
// description cannot be made before the tools are bound).
std::optional<OperationKind> kind_of(const ms::machining_operation& op) {
  if (dynamic_cast<const ts::facing_rough*>(&op)) return OperationKind::facing_rough;
  if (dynamic_cast<const ts::facing_finish*>(&op)) return OperationKind::facing_finish;
  if (dynamic_cast<const ts::contouring_rough*>(&op)) return OperationKind::contouring_rough;
  if (dynamic_cast<const ts::contouring_finish*>(&op)) return OperationKind::contouring_finish;
  if (dynamic_cast<const ts::grooving*>(&op)) return OperationKind::grooving;
  if (dynamic_cast<const milling_schema::center_drilling*>(&op)) return OperationKind::center_drilling;
  return std::nullopt;
}

std::vector<const machining::Executable*> workingsteps_in_order(const machining::Executable& root) {
  std::vector<const machining::Executable*> out;
  const auto walk = [&](const auto& self, const machining::Executable& e) -> void {
    if (e.kind == machining::ExecutableKind::workingstep) out.push_back(&e);
    for (const auto& child : e.children) self(self, child);
  };
  walk(walk, root);
  return out;
}

// The largest finished diameter of a feature: with a constant cutting
// speed the spindle turns slowest there, so the feed per revolution, and
// the roughness, are largest (SEEDS-SPEC 1.5 item 5).
double finished_diameter(const machining::MachiningProject& project, const machining::Feature& feature) {
  if (const auto* profile = std::get_if<machining::TurningProfile>(&feature.shape)) {
    double radius = 0;
    for (const auto& p : profile->points) radius = std::max(radius, p.y);
    return 2 * radius;
  }
  if (const auto* groove = std::get_if<machining::Groove>(&feature.shape)) return 2 * groove->bottom_radius;
  return 2 * project.workpiece.stock_radius;
}

class Planner {
 public:
  Planner(exchange::ModelFile& file, const PlanOptions& options) : model_(file.model), options_(options) {}

  PlanResult run() {
    SequenceResult sequenced = resequence(model_, options_.sequence);
    result_.diagnostics = std::move(sequenced.diagnostics);
    for (SequenceChange& change : sequenced.changes) result_.changes.push_back({change.where, std::move(change.what)});
    result_.tool_changes_before = sequenced.tool_changes_before;
    result_.tool_changes_after = sequenced.tool_changes_after;
    if (!result_.ok()) return std::move(result_);
    bind_late();
    if (!result_.ok()) return std::move(result_);
    machining::DescribeResult described = machining::describe_project(model_);
    result_.diagnostics.insert(result_.diagnostics.end(), described.diagnostics.begin(), described.diagnostics.end());
    if (!described.ok()) return std::move(result_);
    report_and_reduce(described.project);
    if (!result_.ok()) return std::move(result_);
    check_result();
    return std::move(result_);
  }

 private:
  void error(Source where, std::string message) {
    result_.diagnostics.push_back({Diagnostic::Severity::error, std::move(where), std::move(message)});
  }

  // ------------------------------------------------------------ late binding
  void bind_late() {
    std::vector<ms::machining_operation*> operations;
    for (meta::Instance* instance : model_.instances())
      if (auto* op = dynamic_cast<ms::machining_operation*>(instance)) operations.push_back(op);
    std::sort(operations.begin(), operations.end(), [](auto* a, auto* b) { return a->id() < b->id(); });
    for (ms::machining_operation* op : operations) {
      if (op->its_tool && op->its_technology) continue;
      const Source where = source_of(*op, op->its_id.str());
      const std::optional<OperationKind> kind = kind_of(*op);
      if (!kind) {
        error(where, fmt::format("late binding: {} is not a turning operation the planner binds",
                                 op->entity_info().name));
        continue;
      }
      if (!op->its_tool) bind_tool(*op, *kind, where);
      if (!op->its_technology && op->its_tool) bind_technology(*op, *kind, where);
    }
  }

  void bind_tool(ms::machining_operation& op, OperationKind kind, const Source& where) {
    if (!options_.tools) {
      error(where, "has no tool (late binding) and no tool library was given (--tools)");
      return;
    }
    const tooling::Tool* chosen = nullptr;
    std::string why;
    for (const tooling::Tool& tool : options_.tools->tools) {
      if (!tool.available) continue;
      if (kind == OperationKind::grooving) {
        // The narrowest grooving tool fits any groove another one fits.
        if (tool.kind == "grooving_tool" && tool.width && (!chosen || *tool.width < *chosen->width)) chosen = &tool;
        why = "the narrowest available grooving_tool";
      } else if (kind == OperationKind::center_drilling) {
        if (tool.kind == "center_drill" && !chosen) chosen = &tool;
        why = "the first available center_drill";
      } else {
        // The largest nose radius: the strongest edge for roughing, the
        // largest feed for a roughness target when finishing (eq. 1).
        if (tool.kind == "general_turning_tool" && tool.nose_radius && tool.side_cutting_edge_angle &&
            tool.end_cutting_edge_angle && (!chosen || *tool.nose_radius > *chosen->nose_radius))
          chosen = &tool;
        why = "the available general_turning_tool with the largest nose radius (strongest edge; largest feed for "
              "a roughness target)";
      }
    }
    if (!chosen) {
      error(where, fmt::format("late binding: the tool library has no tool for {}", machining::to_string(kind)));
      return;
    }
    op.its_tool = &typed_tool(*chosen);
    result_.changes.push_back(
        {where, fmt::format("tool bound: T{} '{}' ({}, library line {}): {}", chosen->number, chosen->name,
                            chosen->kind, chosen->line, why)});
  }

  ms::cutting_tool& typed_tool(const tooling::Tool& tool) {
    auto [found, added] = tools_.try_emplace(tool.number, nullptr);
    if (added) found->second = &tooling::write_typed_tool(model_, tool);
    return *found->second;
  }

  void bind_technology(ms::machining_operation& op, OperationKind kind, const Source& where) {
    CuttingData data = default_cutting_data(kind);
    std::string why = "the planner's default cutting data for the operation (the tool library has none)";
    if (is_finishing(kind) && options_.roughness) {
      const machining::TurningRoughnessInput tool = turning_input(op, 0);
      if (const auto feed = largest_feed_for(tool, where); feed && *feed < data.feed_per_revolution) {
        data.feed_per_revolution = *feed;
        why += fmt::format("; feed lowered to meet {}", target_text());
      } else if (!feed) {
        return;
      }
    }
    auto& technology = model_.create<ts::turning_technology>();
    technology.feedrate_reference = ms::tool_reference_point::tcp;
    technology.feedrate_per_revolution = data.feed_per_revolution;
    std::string speed;
    if (data.cutting_speed_m_per_min) {
      auto& css = model_.create<ts::const_cutting_speed>();
      css.speed = *data.cutting_speed_m_per_min * m_per_s_per_m_per_min;
      css.max_speed = max_rpm * rev_per_s_per_rpm;
      technology.spindle_speed = &css;
      speed = fmt::format("constant cutting speed {:g} m/min up to {:g} rev/min", *data.cutting_speed_m_per_min, max_rpm);
    } else {
      auto& spindle = model_.create<ts::const_spindle_speed>();
      spindle.rot_speed = *data.spindle_rpm * rev_per_s_per_rpm;
      technology.spindle_speed = &spindle;
      speed = fmt::format("spindle {:g} rev/min", *data.spindle_rpm);
    }
    op.its_technology = &technology;
    result_.changes.push_back({where, fmt::format("technology bound: feed {:g} mm/rev, {}: {}",
                                                  data.feed_per_revolution, speed, why)});
  }

  // The seed's tool data of a typed operation's turning tool; r = -1 when
  // the tool is not a general turning tool with a nose radius.
  static machining::TurningRoughnessInput turning_input(const ms::machining_operation& op, double feed) {
    machining::TurningRoughnessInput in{-1, feed, 0, 0};
    const auto* cutter = dynamic_cast<const ms::cutting_tool*>(op.its_tool);
    const auto* body = cutter ? dynamic_cast<const tt::general_turning_tool*>(cutter->its_tool_body) : nullptr;
    if (body && body->dimension && body->dimension->nose_radius) {
      in.nose_radius = *body->dimension->nose_radius;
      in.side_cutting_edge_deg = body->dimension->side_cutting_edge_angle.value_or(0);
      in.end_cutting_edge_deg = body->dimension->end_cutting_edge_angle.value_or(0);
    }
    return in;
  }

  std::string target_text() const {
    return fmt::format("{} {:g} mm", options_.roughness->measure == machining::RoughnessMeasure::rt ? "Rt" : "Ra",
                       options_.roughness->value);
  }

  // The largest feed meeting the target, rounded down to 0.001 mm/rev.
  std::optional<double> largest_feed_for(const machining::TurningRoughnessInput& tool, const Source& where) {
    machining::TurningRoughnessInput check = tool;
    check.feed_per_revolution = 1;
    if (tool.nose_radius < 0) {
      error(where, "its tool has no nose radius: the roughness target cannot be met or checked");
      return std::nullopt;
    }
    if (const std::string problem = machining::roughness_input_problem(check); !problem.empty()) {
      error(where, fmt::format("its tool is not a turning tool: {}", problem));
      return std::nullopt;
    }
    const auto feed = machining::largest_feed(tool, options_.roughness->measure, options_.roughness->value);
    const double rounded = feed ? std::floor(*feed * 1000 + 1e-9) / 1000 : 0;
    if (rounded < min_finishing_feed) {
      error(where, fmt::format("impossible roughness target {}: it needs a feed below {:g} mm/rev", target_text(),
                               min_finishing_feed));
      return std::nullopt;
    }
    return rounded;
  }

  // -------------------------------------------------- report and feed reduction
  void report_and_reduce(const machining::MachiningProject& project) {
    for (const machining::Executable* e : workingsteps_in_order(project.main_workplan)) {
      const machining::Operation& op = project.operations[e->step.operation];
      if (op.tool < 0) continue;
      const machining::Tool& tool = project.tools[op.tool];
      if (tool.kind != machining::ToolKind::turning_insert && tool.kind != machining::ToolKind::grooving_insert)
        continue;
      const machining::Feature& feature = project.features[e->step.feature];
      WorkingstepRoughness line;
      line.workingstep = e->source;
      line.operation = op.source;
      line.tool = tool.source;
      line.finishing = is_finishing(op.kind);
      const double diameter = finished_diameter(project, feature);
      if (op.technology) line.feed = machining::feed_per_revolution(*op.technology, diameter);
      machining::TurningRoughnessInput in{tool.nose_radius, line.feed.value_or(0), tool.side_cutting_edge_angle_deg,
                                          tool.end_cutting_edge_angle_deg};
      if (!line.feed) {
        line.note = "n/a: the feed per revolution cannot be determined";
      } else if (tool.kind == machining::ToolKind::grooving_insert) {
        line.note = "n/a: a grooving insert's edge angles are not in the model";
      } else if (!has_nose_radius(tool.source)) {
        error(tool.source, fmt::format("turning tool has no nose_radius: the roughness of {} cannot be computed",
                                       e->source.labelled_in_brackets(e->source.name)));
        continue;
      } else if (const std::string problem = machining::roughness_input_problem(in); !problem.empty()) {
        error(op.source, fmt::format("cannot compute the roughness with {}: {}", tool.source.labelled("tool"), problem));
        continue;
      } else {
        if (!op.technology->feed_per_revolution)
          line.note = fmt::format("feed per revolution from the feed rate at diameter {:g} mm", diameter);
        line.roughness = machining::surface_roughness(in);
        if (line.finishing && options_.roughness) reduce_feed(op, in, line, diameter);
      }
      result_.roughness.push_back(std::move(line));
    }
  }

  // Part 121 makes nose_radius optional; the description reads a missing one as 0.
  bool has_nose_radius(const Source& tool) {
    const auto* cutter = dynamic_cast<const ms::cutting_tool*>(instance(tool.id));
    const auto* body = cutter ? dynamic_cast<const tt::turning_machine_tool_body*>(cutter->its_tool_body) : nullptr;
    return body && body->dimension && body->dimension->nose_radius;
  }

  double measured(const machining::Roughness& r) const {
    return options_.roughness->measure == machining::RoughnessMeasure::rt ? r.rt : r.ra;
  }

  void reduce_feed(const machining::Operation& op, machining::TurningRoughnessInput in, WorkingstepRoughness& line,
                   double diameter) {
    if (measured(*line.roughness) <= options_.roughness->value) return;
    const auto feed = largest_feed_for(in, op.source);
    if (!feed) return;
    auto* typed = dynamic_cast<ms::machining_operation*>(instance(op.source.id));
    auto* technology = typed ? dynamic_cast<ts::turning_technology*>(typed->its_technology) : nullptr;
    if (!technology) {
      error(op.source, "its technology is not a turning_technology: the feed cannot be reduced");
      return;
    }
    technology = &own_technology(*typed, *technology);
    const double old_feed = *line.feed;
    if (technology->feedrate_per_revolution) {
      technology->feedrate_per_revolution = *feed;
    } else {
      // A feed rate (m/s): scale it by the feed ratio, spindle speed unchanged.
      *technology->feedrate *= *feed / old_feed;
    }
    const machining::Roughness before = *line.roughness;
    in.feed_per_revolution = *feed;
    line.feed = *feed;
    line.roughness = machining::surface_roughness(in);
    result_.changes.push_back(
        {op.source, fmt::format("feed reduced {:g} -> {:g} mm/rev{}: {} {:.6g} mm missed the target {}; now {:.6g} mm",
                                old_feed, *feed, technology->feedrate_per_revolution ? "" : fmt::format(" (at diameter {:g} mm)", diameter),
                                options_.roughness->measure == machining::RoughnessMeasure::rt ? "Rt" : "Ra",
                                measured(before), target_text(), measured(*line.roughness))});
  }

  // The operation's own technology: a copy when another operation shares it.
  ts::turning_technology& own_technology(ms::machining_operation& op, ts::turning_technology& technology) {
    const auto shared = std::count_if(model_.instances().begin(), model_.instances().end(), [&](meta::Instance* i) {
      auto* other = dynamic_cast<ms::machining_operation*>(i);
      return other && other != &op && other->its_technology == &technology;
    });
    if (shared == 0) return technology;
    auto& copy = model_.create<ts::turning_technology>();
    copy.feedrate = technology.feedrate;
    copy.feedrate_reference = technology.feedrate_reference;
    copy.spindle_speed = technology.spindle_speed;
    copy.feedrate_per_revolution = technology.feedrate_per_revolution;
    copy.sync_spindle_and_z_feed = technology.sync_spindle_and_z_feed;
    copy.inhibit_feedrate_override = technology.inhibit_feedrate_override;
    copy.inhibit_spindle_override = technology.inhibit_spindle_override;
    op.its_technology = &copy;
    result_.changes.push_back({source_of(op, op.its_id.str()),
                               fmt::format("technology #{} is shared: copied to #{} before changing it",
                                           technology.id(), copy.id())});
    return copy;
  }

  meta::Instance* instance(std::optional<std::uint64_t> id) {
    for (meta::Instance* i : model_.instances())
      if (i->id() == id) return i;
    return nullptr;
  }

  // ---------------------------------------------------------- final checks
  void check_result() {
    for (const meta::ValidationProblem& problem : meta::validate(model_))
      error({problem.id, std::string(problem.entity)}, fmt::format("planned model: {}: {}", problem.attribute, problem.message));
    if (!result_.ok()) return;
    const machining::DescribeResult described = machining::describe_project(model_);
    machining::GenerateOptions generate_options;
    generate_options.pass_order = options_.pass_order;
    const machining::GenerateResult generated = machining::generate(described.project, generate_options);
    for (const Diagnostic& d : generated.diagnostics)
      if (d.severity == Diagnostic::Severity::error) result_.diagnostics.push_back(d);
    if (result_.ok() && options_.toolpaths) write_toolpaths(described.project, generated.program);
  }

  // ------------------------------------------------------ explicit toolpaths
  // The generated motion of each workingstep, as runs of rapid and feed
  // moves; the lathe frame is the setup's (x radius, z axis).
  void write_toolpaths(const machining::MachiningProject& project, const machining::Program& program) {
    std::map<std::optional<std::uint64_t>, std::vector<const machining::Move*>> by_workingstep;
    const std::vector<machining::Move> moves = machining::expand_motion(program);
    for (const machining::Move& m : moves) {
      const auto& provenance = program.provenance[program.blocks[m.block].provenance];
      if (provenance.workingstep.id) by_workingstep[provenance.workingstep.id].push_back(&m);
    }
    for (const machining::Executable* e : workingsteps_in_order(project.main_workplan)) {
      const machining::Operation& op = project.operations[e->step.operation];
      auto* typed = dynamic_cast<ms::machining_operation*>(instance(op.source.id));
      if (!typed || typed->its_toolpath || op.tool < 0 || project.machine != machining::MachineKind::turning) continue;
      const auto& ws_moves = by_workingstep[e->source.id];
      const bool plain = std::all_of(ws_moves.begin(), ws_moves.end(), [](const machining::Move* m) {
        return m->kind != machining::Move::Kind::arc && m->kind != machining::Move::Kind::dwell;
      });
      if (!plain) {
        result_.changes.push_back({op.source, "toolpaths not written: its motion has arcs or dwells, which the "
                                              "planner does not write as trajectories yet"});
        continue;
      }
      // Runs of one kind, each starting where the last one ended, from
      // after the tool change (the machine's own retract is not the path's).
      auto start = ws_moves.begin();
      for (auto it = ws_moves.begin(); it != ws_moves.end(); ++it)
        if ((*it)->kind == machining::Move::Kind::tool_change) start = it + 1;
      std::vector<std::pair<bool, std::vector<machining::Vec3>>> runs;  // rapid?, points
      for (auto it = start; it != ws_moves.end(); ++it) {
        const machining::Move* m = *it;
        if (m->kind != machining::Move::Kind::rapid && m->kind != machining::Move::Kind::feed) continue;
        const bool rapid = m->kind == machining::Move::Kind::rapid;
        if (runs.empty()) runs.push_back({rapid, {}});
        else if (runs.back().first != rapid) runs.push_back({rapid, {runs.back().second.back()}});
        runs.back().second.push_back(m->to);
      }
      // A polyline needs two points: a lone first point joins the next run.
      if (runs.size() > 1 && runs.front().second.size() == 1) runs.erase(runs.begin());
      if (runs.empty()) continue;
      auto& list = model_.create<ms::toolpath_list>();
      std::size_t points = 0;
      for (const auto& [rapid, run] : runs) {
        auto& line = model_.create<ms::polyline>();
        line.name = rapid ? "RAPID" : "FEED";
        for (const machining::Vec3& p : run) {
          auto& point = model_.create<ms::cartesian_point>();
          point.coordinates = {p.x, p.y, p.z};
          line.points.push_back(&point);
        }
        points += run.size();
        auto& trajectory = model_.create<ms::cutter_location_trajectory>();
        trajectory.its_priority = true;
        trajectory.its_type = rapid ? ms::toolpath_type::non_contact : ms::toolpath_type::contact;
        trajectory.basiccurve = &line;
        list.its_list.push_back(&trajectory);
      }
      typed->its_toolpath = &list;
      result_.changes.push_back({op.source, fmt::format("explicit toolpaths written: toolpath_list #{}, {} "
                                                        "cutter_location_trajectory ({} points)",
                                                        list.id(), list.its_list.size(), points)});
    }
  }

  meta::Model& model_;
  const PlanOptions& options_;
  PlanResult result_;
  std::map<int, ms::cutting_tool*> tools_;  // library tool number -> bound instance
};

}  // namespace

bool PlanResult::ok() const {
  return std::none_of(diagnostics.begin(), diagnostics.end(),
                      [](const Diagnostic& d) { return d.severity == Diagnostic::Severity::error; });
}

std::optional<RoughnessTarget> parse_roughness_target(std::string_view text, std::string& error) {
  RoughnessTarget target;
  const std::size_t equals = text.find('=');
  const std::string_view name = text.substr(0, equals);
  if (equals == std::string_view::npos || (name != "Rt" && name != "Ra")) {
    error = fmt::format("'{}' is not Rt=VALUE or Ra=VALUE", text);
    return std::nullopt;
  }
  target.measure = name == "Rt" ? machining::RoughnessMeasure::rt : machining::RoughnessMeasure::ra;
  std::string_view value = text.substr(equals + 1);
  double scale = 1;
  if (value.size() > 2 && value.substr(value.size() - 2) == "um") {
    scale = 0.001;
    value.remove_suffix(2);
  } else if (value.size() > 2 && value.substr(value.size() - 2) == "mm") {
    value.remove_suffix(2);
  }
  const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), target.value);
  if (ec != std::errc() || ptr != value.data() + value.size() || !(target.value > 0)) {
    error = fmt::format("'{}': the roughness must be a positive number (mm, or um with the suffix)", text);
    return std::nullopt;
  }
  target.value *= scale;
  return target;
}

bool is_late_binding_gap(const meta::Model& model, const p21::Diagnostic& diagnostic) {
  if (diagnostic.severity != p21::Severity::error) return false;
  for (const meta::Instance* i : model.instances()) {
    if (i->id() != diagnostic.instance_id) continue;
    const auto* op = dynamic_cast<const ms::machining_operation*>(i);
    if (!op) return false;
    return (!op->its_tool && diagnostic.message.find("'its_tool'") != std::string::npos) ||
           (!op->its_technology && diagnostic.message.find("'its_technology'") != std::string::npos);
  }
  return false;
}

PlanResult plan(exchange::ModelFile& file, const PlanOptions& options) { return Planner(file, options).run(); }

}  // namespace stepnc::planning
