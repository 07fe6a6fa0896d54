// SPDX-License-Identifier: Apache-2.0
// Seed 002 §4.2: which operation a workingstep is. Cycles map straight to
// operations (§2.1 "a separate method"; the Fanuc mapping of SEEDS-SPEC
// §2.6); everything else goes through Table 3: strong rules filter the
// candidates the tool allows, weak rules score them, ties go to rough
// before finish and then to table order (decision 2.5.7).
#include <algorithm>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "turning_steps.h"

namespace stepnc::recognize::turning {
namespace {

double word(const gcode::CycleEvent& cycle, char letter, double fallback = 0) {
  for (const auto& [name, value] : cycle.parameters)
    if (name == letter) return value;
  return fallback;
}
bool has_word(const gcode::CycleEvent& cycle, char letter) {
  return std::any_of(cycle.parameters.begin(), cycle.parameters.end(), [&](const auto& p) { return p.first == letter; });
}

bool is_rough(const std::string& operation) { return operation.find("_rough") != std::string::npos; }

// The facts Table 3's rules read.
struct Facts {
  bool general = false, internal = false, grooving = false, drilling = false, centre_drill = false;
  bool perpendicular_to_z = true, axis_aligned = true;
  bool z_decreases = false, x_decreases = false, x_increases = false;
  bool roughing_insert = false, finishing_insert = false;
  bool contour_run = false, dwell = false, first_operation = false;
  std::size_t strokes = 0;
  bool faster_than_roughing = false, rough_in_area = false, centre_drilled = false, drilled = false;
};

struct Rule {
  std::string text;
  bool holds;
};
struct Candidate {
  std::string operation;
  Family family;
  bool internal;
  std::vector<Rule> strong, weak;
};

}  // namespace

void recognise_operation(const Group& group, const std::vector<Group>& groups, std::size_t index,
                         std::span<const Recognised> earlier, const Motion& motion, const gcode::Result& result,
                         const tooling::Tool& tool, Recognised& out, std::vector<Decision>& decisions) {
  const auto lines = lines_of(motion, group.first_move(), group.end_move());
  out.internal = internal_tool(tool);
  const bool synchronised = std::any_of(motion.moves.begin() + static_cast<std::ptrdiff_t>(group.first_move()),
                                        motion.moves.begin() + static_cast<std::ptrdiff_t>(group.end_move()),
                                        [](const Move& m) { return m.synchronised && m.kind == Move::Kind::feed; });
  // The cycle method.
  if (group.cycle >= 0) {
    const gcode::CycleEvent& cycle = result.cycles[static_cast<std::size_t>(group.cycle)];
    const std::string rule = fmt::format("Fanuc cycle method (seed 002 §4.1; SEEDS-SPEC §2.6): {}", cycle.name);
    const std::vector<std::uint32_t> at{cycle.line};
    auto set = [&](std::string operation, Family family, std::string strategy, std::string why) {
      out.operation = std::move(operation);
      out.family = family;
      out.strategy = std::move(strategy);
      decisions.push_back({rule, fmt::format("operation {}, strategy {}: {}", out.operation, out.strategy, why), at});
    };
    if (cycle.name == "G71" || cycle.name == "G72" || cycle.name == "G73") {
      const bool facing = cycle.name == "G72";
      set(facing ? "facing_rough" : "contouring_rough", facing ? Family::facing : Family::contouring,
          cycle.name == "G73" ? "contour_turning" : "unidirectional_perpendicular",
          cycle.name == "G71"   ? "stock removal in turning"
          : cycle.name == "G72" ? "stock removal in facing"
                                : "pattern repeating");
      // Allowances U (diameter) and W; the depth of cut from the first block (0i) or D (0-T).
      out.allowance_x = std::abs(word(cycle, 'U')) / 2;  // negative U: an internal contour
      out.allowance_z = std::abs(word(cycle, 'W'));
      const double depth = has_word(cycle, facing ? 'w' : 'u') ? word(cycle, facing ? 'w' : 'u') : word(cycle, 'D');
      if (depth > 0 && cycle.name != "G73") out.cutting_depths = {depth};
      decisions.push_back({rule, fmt::format("allowance {:g} mm on the radius (U{:g}), {:g} mm in Z (W); depth of cut {:g} mm",
                                             *out.allowance_x, word(cycle, 'U'), *out.allowance_z, depth),
                           at});
    } else if (cycle.name == "G70") {
      set("contouring_finish", Family::contouring, "contour_turning",
          "finishing along the contour N P to N Q");
    } else if (cycle.name == "G74") {
      if (drilling_tool(tool)) {
        set("multistep_drilling", Family::drilling, "", "end face peck drilling on the axis");
        out.peck = has_word(cycle, 'Q') ? word(cycle, 'Q') : word(cycle, 'K');
      } else {
        set("grooving_rough", Family::grooving, "multistep_grooving_strategy", "end face peck grooving");
      }
    } else if (cycle.name == "G75") {
      set("grooving_rough", Family::grooving, "multistep_grooving_strategy", "outer diameter peck grooving");
    } else if (cycle.name == "G76" || cycle.name == "G92") {
      set("threading_rough", Family::contouring, "thread_strategy", "threading (outside the paper's scope, §4)");
    } else if (cycle.name == "G90") {
      set("contouring_rough", Family::contouring, "unidirectional_perpendicular", "outer diameter turning cycle");
    } else if (cycle.name == "G94") {
      set("facing_rough", Family::facing, "unidirectional_perpendicular", "end face turning cycle");
    } else {
      set("contouring_rough", Family::contouring, "explicit_turning_strategy", "a cycle without a mapping");
      out.fallback = true;
    }
    return;
  }
  if (synchronised) {
    out.operation = "threading_rough";
    out.family = Family::contouring;
    out.strategy = "thread_strategy";
    decisions.push_back({"project rule: spindle-synchronised motion (G32)", "operation threading_rough", lines});
    return;
  }

  // Table 3.
  Facts f;
  f.drilling = drilling_tool(tool);
  f.centre_drill = tool.kind == "center_drill";
  f.grooving = tool.kind == "grooving_tool";
  f.internal = out.internal && !f.drilling;
  f.general = !f.drilling && !f.grooving && !f.internal && tool.kind != "threading_tool";
  f.roughing_insert = tool.nose_radius && *tool.nose_radius >= 0.8 - 1e-9;
  f.finishing_insert = tool.nose_radius && *tool.nose_radius <= 0.4 + 1e-9;
  f.first_operation = index == 0;
  std::vector<const Move*> leads;
  for (const Stroke& s : group.strokes) {
    if (s.first_interpolation >= s.end) continue;
    leads.push_back(&motion.moves[s.first_interpolation]);
    f.contour_run = f.contour_run || s.longest_run > 2;
  }
  f.strokes = leads.size();
  for (const Move* m : leads) {
    const Axis axis = dominant_axis(trajectory_angle(m->from, m->to));
    f.perpendicular_to_z = f.perpendicular_to_z && (axis == Axis::minus_x || axis == Axis::plus_x);
    f.axis_aligned = f.axis_aligned && axis != Axis::diagonal;
  }
  if (leads.size() >= 2) {
    f.z_decreases = f.x_decreases = f.x_increases = true;
    for (std::size_t i = 1; i < leads.size(); ++i) {
      const double x0 = std::min(leads[i - 1]->from.x, leads[i - 1]->to.x), x1 = std::min(leads[i]->from.x, leads[i]->to.x);
      f.z_decreases = f.z_decreases && leads[i]->from.z < leads[i - 1]->from.z;
      f.x_decreases = f.x_decreases && x1 < x0;
      f.x_increases = f.x_increases && std::max(leads[i]->from.x, leads[i]->to.x) >
                                           std::max(leads[i - 1]->from.x, leads[i - 1]->to.x);
    }
  }
  for (std::size_t i = group.first_move(); i < group.end_move(); ++i) f.dwell = f.dwell || motion.moves[i].kind == Move::Kind::dwell;
  const Box& box = group.cut;
  const gcode::MotionState& state = leads.empty() ? motion.moves[group.first_move()].state : leads.front()->state;
  auto family_of = [](const std::string& op) {
    if (op.rfind("facing", 0) == 0) return Family::facing;
    if (op.rfind("grooving", 0) == 0) return Family::grooving;
    if (op.find("drilling") != std::string::npos) return Family::drilling;
    return Family::contouring;
  };
  auto faster = [&](Family family, bool internal) {
    for (std::size_t g = 0; g < earlier.size(); ++g) {
      const Recognised& e = earlier[g];
      if (e.family != family || e.internal != internal || !is_rough(e.operation)) continue;
      const Group& other = groups[g];
      const gcode::MotionState& rough = motion.moves[other.strokes.front().first_interpolation < other.strokes.front().end
                                                        ? other.strokes.front().first_interpolation
                                                        : other.first_move()]
                                            .state;
      if ((state.css == rough.css && state.spindle > rough.spindle) || state.feed < rough.feed) return true;
    }
    return false;
  };
  auto rough_in_area = [&](Family family, bool internal) {
    for (std::size_t g = 0; g < earlier.size(); ++g)
      if (earlier[g].family == family && earlier[g].internal == internal && is_rough(earlier[g].operation) &&
          groups[g].cut.overlaps(box))
        return true;
    return false;
  };
  for (const Recognised& e : earlier) {
    f.centre_drilled = f.centre_drilled || e.operation == "center_drilling";
  }
  const Rule several{"several strokes (Def. 4: a roughing operation consists of several strokes)", f.strokes >= 2};
  const Rule single{"a single stroke (Def. 4)", f.strokes == 1};
  const bool outside_faster = faster(Family::facing, false), contour_faster = faster(Family::contouring, false);
  std::vector<Candidate> candidates{
      {"facing_rough", Family::facing, false,
       {{"use of general turning tool", f.general}, {"machining movement perpendicular to Z axis", f.perpendicular_to_z}},
       {{"use of roughing turning tool (nose radius >= 0.8 mm)", f.roughing_insert},
        {"the first machining operation", f.first_operation},
        {"Z values of interpolation blocks decrease", f.z_decreases},
        several}},
      {"facing_finish", Family::facing, false,
       {{"use of general turning tool", f.general}, {"machining movement perpendicular to Z axis", f.perpendicular_to_z}},
       {{"use of finishing turning tool (nose radius <= 0.4 mm)", f.finishing_insert},
        {"faster spindle speed or lower feedrate than roughing", outside_faster},
        {"a roughing operation in the same machining area (§4.2)", rough_in_area(Family::facing, false)},
        single}},
      {"contouring_rough", Family::contouring, false,
       {{"use of general turning tool", f.general}},
       {{"use of roughing turning tool (nose radius >= 0.8 mm)", f.roughing_insert},
        {"X values of interpolation blocks decrease", f.x_decreases},
        several}},
      {"contouring_finish", Family::contouring, false,
       {{"use of general turning tool", f.general},
        {"the contour turning strategy (more than 2 interpolations in a row)", f.contour_run}},
       {{"use of finishing turning tool (nose radius <= 0.4 mm)", f.finishing_insert},
        {"faster spindle speed or lower feedrate than roughing", contour_faster},
        {"a roughing operation in the same machining area (§4.2)", rough_in_area(Family::contouring, false)},
        single}},
      {"grooving_rough", Family::grooving, false,
       {{"use of grooving tool", f.grooving}},
       {{"machining direction perpendicular to Z axis or X axis", f.axis_aligned}, several}},
      {"grooving_finish", Family::grooving, false,
       {{"use of grooving tool", f.grooving}},
       {{"faster spindle speed or lower feedrate than roughing", faster(Family::grooving, false)},
        {"a roughing operation in the same machining area (§4.2)", rough_in_area(Family::grooving, false)},
        {"project rule: a dwell at the bottom (a finishing plunge)", f.dwell},
        single}},
      {"contouring_rough", Family::contouring, true,
       {{"use of internal turning tool", f.internal}},
       {{"post-operation of a drilling operation", f.centre_drilled || std::any_of(earlier.begin(), earlier.end(), [](const Recognised& e) { return e.family == Family::drilling; })},
        {"use of internal roughing turning tool (nose radius >= 0.8 mm)", f.roughing_insert},
        {"X values of interpolation blocks increase", f.x_increases},
        several}},
      {"contouring_finish", Family::contouring, true,
       {{"use of internal turning tool", f.internal},
        {"the contour turning strategy (more than 2 interpolations in a row)", f.contour_run}},
       {{"use of internal finishing turning tool (nose radius <= 0.4 mm)", f.finishing_insert},
        {"faster spindle speed or lower feedrate than roughing", faster(Family::contouring, true)},
        {"a roughing operation in the same machining area (§4.2)", rough_in_area(Family::contouring, true)},
        single}},
      {"center_drilling", Family::drilling, false, {{"use of centre drill", f.centre_drill}}, {}},
      {"drilling", Family::drilling, false,
       {{"use of drilling tool", f.drilling && !f.centre_drill}},
       {{"centre drilling as the pre-operation", f.centre_drilled}, single}},
      {"multistep_drilling", Family::drilling, false,
       {{"use of drilling tool", f.drilling && !f.centre_drill}},
       {{"centre drilling as the pre-operation", f.centre_drilled},
        {"multistep drilling for easy chip removal (several pecks)", f.strokes >= 2}}},
  };
  const Candidate* best = nullptr;
  std::size_t best_score = 0;
  for (const Candidate& c : candidates) {
    const std::string name = fmt::format("{}{}", c.internal ? "internal " : "", c.operation);
    const auto failed = std::find_if(c.strong.begin(), c.strong.end(), [](const Rule& r) { return !r.holds; });
    if (failed != c.strong.end()) continue;
    for (const Rule& r : c.strong)
      decisions.push_back({fmt::format("seed 002 Table 3 {} (strong)", name), r.text + ": holds", lines});
    std::size_t score = 0;
    for (const Rule& r : c.weak)
      if (r.holds) {
        ++score;
        decisions.push_back({fmt::format("seed 002 Table 3 {} (weak)", name), r.text + ": holds", lines});
      }
    // Ties: rough before finish, then table order (decision 2.5.7).
    if (!best || score > best_score || (score == best_score && is_rough(c.operation) && !is_rough(best->operation))) {
      best = &c;
      best_score = score;
    }
  }
  if (!best) {
    out.fallback = true;
    out.family = f.grooving ? Family::grooving : f.drilling ? Family::drilling : Family::contouring;
    out.operation = f.grooving ? "grooving_rough" : f.drilling ? "drilling" : "contouring_rough";
    out.strategy = f.drilling ? "" : "explicit_turning_strategy";
    decisions.push_back({"seed 002 Table 3 (no candidate's strong rules hold)",
                         fmt::format("kept as {} with its explicit toolpath, nothing lost", out.operation), lines});
    return;
  }
  out.operation = best->operation;
  out.family = family_of(best->operation);
  if (is_rough(out.operation))
    decisions.push_back({"ISO 14649-12 " + out.operation + ".wr1 (a roughing operation states its allowance)",
                         "allowance 0: the motion does not say what the finish leaves", {}});
  decisions.push_back({"decision 2.5.7 (strong rules filter, most weak rules win, rough before finish, table order)",
                       fmt::format("operation {}{} with {} weak rule(s)", best->internal ? "internal " : "",
                                   best->operation, best_score),
                       lines});
}

}  // namespace stepnc::recognize::turning
